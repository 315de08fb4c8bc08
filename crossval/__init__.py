"""Cross-validation harness: run scenes through the methods and check them against theory."""
from .compare import Check, Comparison, compare
from .methods import METHODS, applicable_methods, get_method
from .reference import Reference, assert_matches_reference, reference
from .suite import SUITE
from . import regress, report, study  # noqa: F401  (submodules of the library API)

__all__ = ["METHODS", "applicable_methods", "get_method", "compare", "Check", "Comparison", "reference",
           "Reference", "assert_matches_reference", "SUITE"]
