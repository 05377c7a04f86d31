"""Speed targets of issue 7 (a script, not a test): prints each measured number with PASS/FAIL.

Same as ``sawdrift bench speed [--quick]``.

Run: ``python benchmarks/bench_speed.py [--quick] [--json speed.json]``
"""

from __future__ import annotations

import argparse
import sys

from sawdrift.bench import speed


def main(argv: list[str] | None = None) -> int:
    """Parse the options, run :func:`sawdrift.bench.speed`; exit status 1 if a target fails."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small variants (seconds, for CI)")
    parser.add_argument("--json", default=None, help="also write the results to this JSON file")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars")
    args = parser.parse_args(argv)
    result = speed(args.quick, progress=not args.no_progress, out=args.json)
    return 0 if result["all_passed"] else 1


if __name__ == "__main__":
    sys.exit(main())
