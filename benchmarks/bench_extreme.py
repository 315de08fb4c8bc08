"""Stiff and extreme cases: converged or not, error against theory, iterations, time.
(The same table is part of the full report: ``crossval report``.)

    python benchmarks/bench_extreme.py [--update]

``--update`` writes docs/accuracy_extreme.json (rendered into docs/accuracy.md by
``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import sys

import _timing

from crossval.extremes import HEADERS, extreme_cases


def main(update=False):
    record = _timing.provenance_record()
    rows = extreme_cases()
    print(_timing.table(rows, HEADERS))
    if update:
        _timing.write_doc_table("accuracy_extreme", HEADERS, rows, record)


if __name__ == "__main__":
    main(update="--update" in sys.argv)
