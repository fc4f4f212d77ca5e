"""Animation of the mechanism over a cranesim run, written as GIF (or MP4 with ffmpeg).

Same drawing as plot_snapshot.py, one frame per K-th sample (the last sample is
always included), with axis limits fixed over the whole run.

Example:

    python scripts/animate.py run.h5 -o run.gif --fps 25 --every 4 --view 20 -60
"""

import argparse
import shutil
import sys
from pathlib import Path

from matplotlib.animation import FFMpegWriter, FuncAnimation, PillowWriter

from cranesim.results import Results, ResultsError, run_command
from mechanism_drawing import MechanismDrawing, MechanismGeometry, create_figure, set_equal_limits


def parse_arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("results", help="results file (.h5)")
    parser.add_argument(
        "-o", "--output", help="output .gif or .mp4 (default: <results>_animation.gif)"
    )
    parser.add_argument("--fps", type=float, default=20, help="frames per second (default: 20)")
    parser.add_argument(
        "--every", type=int, default=1, metavar="K", help="use every K-th sample (default: 1)"
    )
    parser.add_argument(
        "--view", type=float, nargs=2, metavar=("ELEV", "AZIM"),
        help="camera elevation and azimuth in degrees",
    )
    args = parser.parse_args()
    if args.every < 1 or args.fps <= 0:
        parser.error("--every must be >= 1 and --fps > 0")
    return args


def movie_writer(output: Path, fps: float):
    suffix = output.suffix.lower()
    if suffix == ".gif":
        return PillowWriter(fps=fps)
    if suffix == ".mp4":
        if shutil.which("ffmpeg") is None:
            raise ResultsError("writing .mp4 needs ffmpeg on PATH (not found); use .gif instead")
        return FFMpegWriter(fps=fps)
    raise ResultsError(f"unsupported output type '{output.suffix}' for {output}; use .gif or .mp4")


def frame_samples(sample_count: int, every: int) -> list[int]:
    samples = list(range(0, sample_count, every))
    if samples[-1] != sample_count - 1:
        samples.append(sample_count - 1)
    return samples


def main() -> None:
    args = parse_arguments()
    results_path = Path(args.results)
    output = Path(args.output or results_path.with_name(f"{results_path.stem}_animation.gif"))
    writer = movie_writer(output, args.fps)
    with Results(results_path) as results:
        geometry = MechanismGeometry.load(results)
    figure, axes = create_figure(args.view)
    drawing = MechanismDrawing(axes, geometry, title=results_path.name)
    set_equal_limits(axes, geometry.all_points())
    samples = frame_samples(geometry.time.size, args.every)
    animation = FuncAnimation(figure, drawing.update, frames=samples, blit=False)
    animation.save(output, writer=writer, dpi=80)
    span = f"t = {geometry.time[0]:.6g} .. {geometry.time[-1]:.6g} s"
    print(f"wrote {output} ({len(samples)} frames, {span})")


if __name__ == "__main__":
    sys.exit(run_command(main))
