#!/usr/bin/python3
"""Speed against error: how fast a kdray render converges to a reference.

  speed_vs_error.py run SCENE.kdscene SCENE.kdtree --csv OUT.csv [options] [-- kdrender options]
      Renders 1, 2, 4, ... --max-spp samples per pixel, reusing what is rendered: after the
      first sample, each step renders only the new range [n, 2n) (kdrender --spp n
      --sample-offset n) and merges it exactly into the first n samples, so the image at 2n spp
      is byte for byte the one a single 2n-spp render gives. Each step is compared against the
      reference with kdcompare and written as a CSV row: spp, seconds (cumulative render time
      kdrender reports, without loading or kernel builds), wall_seconds (cumulative wall-clock
      time of the kdrender runs, everything included) and kdcompare's overall metrics. Without
      --reference it renders its own, with --reference-spp samples and a different seed, and
      says so in the CSV header. --sampler picks kdrender's sampler for the series only; the own
      reference always uses the default one, so series of both samplers share one reference.

  speed_vs_error.py plot OUT.csv [MORE.csv ...] -o PLOT.png [--metric relmse]
      Log-log plot of error against seconds, one line per CSV, with a 1/t slope for comparison.

Debian's matplotlib belongs to /usr/bin/python3, hence the interpreter line.
"""

import argparse
import csv
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
METRICS = ["rmse", "relmse", "mae", "psnr", "max_abs"]


def fail(message):
    sys.exit(f"speed_vs_error: error: {message}")


def default_tool(name):
    for build in ("build", "build-release"):
        path = os.path.join(REPO, build, "tools", name, name)
        if os.access(path, os.X_OK):
            return path
    return name  # on PATH


def run_tool(command):
    """Runs a tool, returns (parsed --json stdout, wall seconds); stops on failure."""
    start = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - start
    if result.returncode != 0:
        fail(f"{' '.join(command)} exited {result.returncode}: {result.stderr.strip()}")
    return json.loads(result.stdout), wall


class Renderer:
    """kdrender with the settings every step of one report shares."""

    def __init__(self, args):
        self.kdrender = args.kdrender
        self.common = [args.scene, args.tree, "--width", str(args.width), "--height", str(args.height),
                       "--max-bounces", str(args.max_bounces), "--quiet", "--json"]
        if args.device:
            self.common += ["--device", args.device]
        self.common += args.kdrender_args
        self.series = ["--sampler", args.sampler] if args.sampler else []

    def render(self, output, spp, offset, seed, series=True):
        """Renders samples offset..offset+spp-1 to output (with the series' sampler unless
        series is False); returns (render seconds, wall seconds)."""
        report, wall = run_tool([self.kdrender, *self.common, *(self.series if series else []), "--spp", str(spp),
                                 "--sample-offset", str(offset), "--seed", str(seed), "-o", output])
        return float(report["render_seconds"]), wall

    def merge(self, first, second, output):
        """Merges two adjacent sample ranges exactly (kdrender's fixed-point sums)."""
        _, wall = run_tool([self.kdrender, "--merge", first, second, "-o", output, "--quiet", "--json"])
        return wall


def compare(kdcompare, test, reference):
    report, _ = run_tool([kdcompare, test, reference, "--json"])
    return report


def own_reference(args, renderer, directory):
    """Renders (or reuses, when newer than the scene and tree) the script's own reference. Its
    name carries every setting, the extra kdrender options as a hash, so a stale one is not reused."""
    options = hashlib.sha1(" ".join([args.device or ""] + args.kdrender_args).encode()).hexdigest()[:8]
    name = (f"{os.path.splitext(os.path.basename(args.scene))[0]}-reference-{args.reference_spp}spp"
            f"-seed{args.reference_seed}-{args.width}x{args.height}-b{args.max_bounces}-{options}.exr")
    path = os.path.join(directory, name)
    inputs_mtime = max(os.path.getmtime(args.scene), os.path.getmtime(args.tree))
    if os.path.exists(path) and os.path.getmtime(path) > inputs_mtime:
        print(f"speed_vs_error: reusing {path}", file=sys.stderr)
        return path, None
    print(f"speed_vs_error: rendering the reference, {args.reference_spp} spp ...", file=sys.stderr)
    seconds, _ = renderer.render(path, args.reference_spp, 0, args.reference_seed, series=False)
    return path, seconds


def command_run(args):
    if args.max_spp < 1 or args.max_spp & (args.max_spp - 1):
        fail(f"--max-spp must be a power of two, got {args.max_spp}")
    if args.reference is None and args.reference_seed == args.seed:
        fail("the reference must use another seed than the test renders (--reference-seed)")
    renderer = Renderer(args)
    csv_directory = os.path.dirname(os.path.abspath(args.csv))
    os.makedirs(csv_directory, exist_ok=True)

    header = [f"scene: {args.scene}", f"tree: {args.tree}",
              f"settings: {args.width}x{args.height}, max bounces {args.max_bounces}, seed {args.seed}, "
              f"sampler {args.sampler or 'default'}, "
              f"spp 1..{args.max_spp} doubling, each step renders only the new samples and merges them",
              "seconds: cumulative kdrender render time; wall_seconds: cumulative wall-clock of the kdrender runs "
              "(scene load, kernel build and merges included)"]
    if args.reference:
        reference = args.reference
        header.append(f"reference: given, {reference}")
    else:
        reference, seconds = own_reference(args, renderer, args.reference_dir or csv_directory)
        header.append(f"reference: rendered by this script, {args.reference_spp} spp with seed {args.reference_seed} "
                      f"(the test renders use seed {args.seed}), {os.path.basename(reference)}"
                      + (f", {seconds:.2f} s render time" if seconds is not None else ", reused from an earlier run"))

    rows = []
    with tempfile.TemporaryDirectory(prefix="kdray-speed-vs-error-") as work:
        accumulated = os.path.join(work, "accumulated.exr")
        seconds, wall = renderer.render(accumulated, 1, 0, args.seed)
        spp = 1
        while True:
            metrics = compare(args.kdcompare, accumulated, reference)
            rows.append({"spp": spp, "seconds": round(seconds, 6), "wall_seconds": round(wall, 3),
                         **{name: metrics[name] for name in METRICS}, "nonfinite": metrics["nonfinite_test"]})
            print(f"speed_vs_error: {spp:6d} spp  {seconds:9.3f} s  relmse {metrics['relmse']:.4g}", file=sys.stderr)
            if spp * 2 > args.max_spp:
                break
            new_range = os.path.join(work, "range.exr")
            step_seconds, step_wall = renderer.render(new_range, spp, spp, args.seed)
            merged = os.path.join(work, "merged.exr")
            wall += step_wall + renderer.merge(accumulated, new_range, merged)
            os.replace(merged, accumulated)
            seconds += step_seconds
            spp *= 2
        if args.keep_image:
            os.replace(accumulated, args.keep_image)

    temporary = args.csv + ".tmp"
    with open(temporary, "w", newline="") as out:
        for line in header:
            out.write(f"# {line}\n")
        writer = csv.DictWriter(out, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({key: ("" if value is None else value) for key, value in row.items()})
    os.replace(temporary, args.csv)
    print(f"speed_vs_error: wrote {args.csv}", file=sys.stderr)


def read_rows(path):
    with open(path, newline="") as source:
        return list(csv.DictReader(line for line in source if not line.startswith("#")))


def command_plot(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6.4, 4.8))
    for path in args.csv:
        rows = [row for row in read_rows(path) if row[args.metric] not in ("", None)]
        if not rows:
            fail(f"{path}: no rows with {args.metric}")
        seconds = [float(row["seconds"]) for row in rows]
        errors = [float(row[args.metric]) for row in rows]
        label = os.path.splitext(os.path.basename(path))[0]
        axes.loglog(seconds, errors, marker="o", label=label)
        for row, x, y in zip(rows, seconds, errors):
            axes.annotate(row["spp"], (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
        # The slope an unbiased Monte Carlo estimate follows for MSE-like metrics: error ~ 1/time.
        if args.metric in ("relmse",):
            axes.loglog(seconds, [errors[0] * seconds[0] / s for s in seconds], linestyle=":", color="grey")
    axes.set_xlabel("render seconds (cumulative)")
    axes.set_ylabel(args.metric)
    axes.set_title(args.title or f"{args.metric} against render time")
    axes.grid(True, which="both", linewidth=0.3)
    axes.legend()
    figure.tight_layout()
    temporary = args.output + ".tmp.png"
    figure.savefig(temporary, dpi=args.dpi)
    os.replace(temporary, args.output)
    print(f"speed_vs_error: wrote {args.output}", file=sys.stderr)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)

    run = commands.add_parser("run", help="render a doubling spp series and write the error CSV")
    run.add_argument("scene", help="SCENE.kdscene")
    run.add_argument("tree", help="SCENE.kdtree")
    run.add_argument("--csv", required=True, help="output CSV")
    run.add_argument("--max-spp", type=int, default=256, help="last sample count, a power of two (default 256)")
    run.add_argument("--width", type=int, default=256, help="default 256")
    run.add_argument("--height", type=int, default=256, help="default 256")
    run.add_argument("--max-bounces", type=int, default=8, help="default 8")
    run.add_argument("--seed", type=int, default=0, help="seed of the test renders (default 0)")
    run.add_argument("--reference", help="reference image; default: render one (see --reference-spp)")
    run.add_argument("--reference-spp", type=int, default=4096, help="own reference's samples (default 4096)")
    run.add_argument("--reference-seed", type=int, default=1, help="own reference's seed (default 1)")
    run.add_argument("--reference-dir", help="where the own reference is kept (default: beside the CSV)")
    run.add_argument("--keep-image", help="also write the final max-spp image here (EXR)")
    run.add_argument("--device", help="kdrender --device")
    run.add_argument("--sampler", choices=["sobol", "independent"], help="kdrender --sampler of the series")
    run.add_argument("--kdrender", default=default_tool("kdrender"), help="kdrender executable")
    run.add_argument("--kdcompare", default=default_tool("kdcompare"), help="kdcompare executable")
    run.set_defaults(handler=command_run)

    plot = commands.add_parser("plot", help="log-log plot of error against seconds")
    plot.add_argument("csv", nargs="+", help="CSV files written by 'run'")
    plot.add_argument("-o", "--output", required=True, help="output PNG")
    plot.add_argument("--metric", default="relmse", choices=METRICS, help="default relmse")
    plot.add_argument("--title")
    plot.add_argument("--dpi", type=int, default=120)
    plot.set_defaults(handler=command_plot)

    # Everything after "--" goes to every kdrender run (camera, --stack-size...).
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    args = parser.parse_args(argv[:len(argv) - len(extra) - (1 if "--" in argv else 0)])
    args.kdrender_args = extra
    args.handler(args)


if __name__ == "__main__":
    main()
