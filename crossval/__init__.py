"""Cross-validation harness: run scenes through the methods and check them against theory."""

from .compare import Check, Comparison, compare
from .methods import METHODS, applicable_methods, get_method
from .reference import Reference, UncheckedWarning, assert_matches_reference, reference
from .regress import regress
from .report import report
from .study import study
from .suite import SUITE

# the functions, not their modules, are the library API (modules stay importable as crossval.report etc.)
__all__ = [
    "METHODS",
    "applicable_methods",
    "get_method",
    "compare",
    "Check",
    "Comparison",
    "reference",
    "Reference",
    "assert_matches_reference",
    "UncheckedWarning",
    "SUITE",
    "study",
    "report",
    "regress",
]
