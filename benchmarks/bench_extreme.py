"""Stiff and extreme cases: converged or not, error against theory, iterations, time.
(The same table is part of the full report: ``crossval report``.)

    python benchmarks/bench_extreme.py
"""

from __future__ import annotations

import _timing  # noqa: F401

from crossval.extremes import HEADERS, extreme_cases


def main():
    print(_timing.table(extreme_cases(), HEADERS))


if __name__ == "__main__":
    main()
