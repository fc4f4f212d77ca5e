"""3-D snapshot of the mechanism at one time of a cranesim run.

Draws each body as segments from its origin to its joints, joints as dots,
ground joints as triangles and constraints as crosses, at the sample nearest
to the requested time (default: the last one).

Example:

    python scripts/plot_snapshot.py run.h5 --time 2.5 -o run_t2.5.png
"""

import argparse
import sys
from pathlib import Path

from cranesim.results import Results, run_command
from mechanism_drawing import MechanismDrawing, MechanismGeometry, create_figure, set_equal_limits


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("results", help="results file (.h5)")
    parser.add_argument(
        "--time", type=float, help="time in s; the nearest sample is drawn (default: last)"
    )
    parser.add_argument("-o", "--output", help="output image (default: <results>_snapshot.png)")
    return parser.parse_args()


def main() -> None:
    args = parse_arguments()
    results_path = Path(args.results)
    output = args.output or results_path.with_name(f"{results_path.stem}_snapshot.png")
    with Results(results_path) as results:
        geometry = MechanismGeometry.load(results)
    sample = geometry.time.size - 1 if args.time is None else geometry.nearest_sample(args.time)
    figure, axes = create_figure()
    MechanismDrawing(axes, geometry, title=results_path.name).update(sample)
    set_equal_limits(axes, geometry.all_points(sample))
    figure.savefig(output, dpi=100)
    print(f"wrote {output} (t = {geometry.time[sample]:.6g} s)")


if __name__ == "__main__":
    sys.exit(run_command(main))
