"""Work-precision study of issue 7 (a script, not a test): CSV, figures and a summary.

Same as ``sawdrift bench work-precision [--models a,b] [--quick] -o DIR``.

Run: ``python benchmarks/bench_work_precision.py [--models mmd,mdr] [--quick] -o bench_out``
"""

from __future__ import annotations

import argparse
import sys

from sawdrift.bench import work_precision


def main(argv: list[str] | None = None) -> int:
    """Parse the options and run :func:`sawdrift.bench.work_precision`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", default=None, help="comma-separated model names (default: all "
                        "built-in models)")
    parser.add_argument("--quick", action="store_true", help="short ladders (seconds, for CI)")
    parser.add_argument("-o", "--out", default="bench_out", help="output directory")
    parser.add_argument("--no-defaults-check", action="store_true",
                        help="skip the check of the defaults over the (m*, A*) plane")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars")
    args = parser.parse_args(argv)
    frame = work_precision(args.models, args.out, args.quick, progress=not args.no_progress,
                           defaults_check=not args.no_defaults_check)
    print(f"{len(frame)} runs; wrote {args.out}/work_precision.csv, orders.csv, summary.md and "
          "the figures work_precision_prescribed.png, work_precision_wave.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
