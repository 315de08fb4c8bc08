import sys
from pathlib import Path

# examples/ are importable scripts (documentation that is tested)
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
pytest_plugins = ["pytester"]
