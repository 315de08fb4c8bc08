"""JSON that strict parsers accept: what the package writes for other programs to read.

Python's ``json`` writes NaN and Infinity as bare tokens, which RFC 8259 parsers (JavaScript's
``JSON.parse``, jq, Go, Rust's serde) refuse.  A quantity that is not a finite number (a rate
that could not be fitted, an error with no reference) is written as ``null``: "no value".
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

__all__ = ["to_plain", "dumps"]


def to_plain(obj: Any) -> Any:
    """``obj`` with numpy scalars and arrays turned into Python numbers and lists, tuples into
    lists, and every non-finite float into None."""
    if isinstance(obj, dict):
        return {str(k): to_plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_plain(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        return v if math.isfinite(v) else None
    return obj


def dumps(obj: Any, **kw) -> str:
    """``json.dumps`` of :func:`to_plain` (``obj``), refusing anything that is not plain data."""
    return json.dumps(to_plain(obj), allow_nan=False, **kw)
