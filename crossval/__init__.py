"""Cross-validation harness: run scenes through the methods and check them against theory."""
from .methods import METHODS, applicable_methods, get_method

__all__ = ["METHODS", "applicable_methods", "get_method"]
