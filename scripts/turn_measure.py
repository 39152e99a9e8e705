"""How a turning part turns from frame to frame in `ibfvs render`'s
pictures, and whether its texture turns with it (docs/cfd.md, "Moving
machinery"; tests/corpus/test_moving_propeller.py measures with it).

The part is seen along its axis against a plain background (render with
--background 1,0,1): for each pair of consecutive frames it prints the turn
that best maps the first silhouette onto the second (degrees, to 0.05), and
the correlation of the second picture with the first turned by the part's
turn per frame (with it) and left where it was (left). A part whose steps
play as surfaces of their own stands still for a step's frames and then
jumps, its texture left in the image.

  python3 scripts/turn_measure.py 'f*.png' --degrees-per-frame 0.72

Debian's Python with numpy; ffmpeg decodes the pictures.
"""
import argparse
import glob
import subprocess

import numpy as np


def read_rgb(path):
    """A PNG as float RGB (rows top first), through ffmpeg."""
    probe = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries",
                            "stream=width,height", "-of", "csv=p=0", path],
                           capture_output=True, text=True, check=True).stdout
    width, height = (int(v) for v in probe.strip().split(","))
    raw = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt",
                          "rgb24", "-"], capture_output=True, check=True).stdout
    return np.frombuffer(raw, np.uint8).reshape(height, width, 3).astype(float)


def surface(picture):
    """The pixels unlike the background (read at the first pixel)."""
    return np.abs(picture - picture[0, 0]).max(axis=-1) > 40


def centre_of(mask):
    ys, xs = np.nonzero(mask)
    return xs.mean(), ys.mean()


def turned(values, degrees, centre):
    """`values` turned by `degrees` about `centre` (x, y in pixels),
    bilinear; NaN off the picture."""
    h, w = values.shape
    t = np.radians(degrees)
    y, x = np.mgrid[0:h, 0:w].astype(float)
    dx, dy = x - centre[0], y - centre[1]
    sx = centre[0] + np.cos(t) * dx + np.sin(t) * dy
    sy = centre[1] - np.sin(t) * dx + np.cos(t) * dy
    x0, y0 = np.floor(sx).astype(int), np.floor(sy).astype(int)
    fx, fy = sx - x0, sy - y0
    inside = (x0 >= 0) & (y0 >= 0) & (x0 < w - 1) & (y0 < h - 1)
    x0, y0 = np.clip(x0, 0, w - 2), np.clip(y0, 0, h - 2)
    v = (values[y0, x0] * (1 - fx) * (1 - fy) + values[y0, x0 + 1] * fx * (1 - fy) +
         values[y0 + 1, x0] * (1 - fx) * fy + values[y0 + 1, x0 + 1] * fx * fy)
    return np.where(inside, v, np.nan)


def silhouette_turn(a, b, centre, most=3.0):
    """The turn (degrees, within +-most) that best maps silhouette a onto b:
    the middle of the angles of the best overlap, to 0.05 degrees."""
    angles = np.arange(-most, most + 1e-4, 0.05)
    overlap = []
    for d in angles:
        r = turned(a.astype(float), d, centre) > 0.5
        overlap.append((r & b).sum() / max((r | b).sum(), 1))
    overlap = np.array(overlap)
    return float(angles[overlap >= overlap.max() - 1e-9].mean())


def texture_turn(before, after, mask_before, mask_after, degrees, centre):
    """Correlation of `after` with `before` turned by `degrees` (the better
    of +degrees and -degrees: the camera's handedness), and left in place,
    over the pixels the surface covers in both."""
    def correlation(a, b, mask):
        return float(np.corrcoef(a[mask], b[mask])[0, 1])

    with_it = -1.0
    for d in (degrees, -degrees):
        t = turned(before, d, centre)
        both = mask_after & ~np.isnan(t) & (turned(mask_before.astype(float), d, centre) > 0.99)
        with_it = max(with_it, correlation(t, after, both))
    return with_it, correlation(before, after, mask_before & mask_after)


def measure(paths, degrees_per_frame):
    """Per pair of frames: (silhouette turn, correlation turned with the
    part, left in place)."""
    pictures = [read_rgb(p) for p in paths]
    grey = [p.mean(axis=-1) for p in pictures]
    masks = [surface(p) for p in pictures]
    centre = centre_of(masks[0])
    rows = []
    for k in range(len(paths) - 1):
        turn = silhouette_turn(masks[k], masks[k + 1], centre)
        with_it, left = texture_turn(grey[k], grey[k + 1], masks[k], masks[k + 1],
                                     degrees_per_frame, centre)
        rows.append((turn, with_it, left))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("frames", help="the frames, a glob pattern (in order by name)")
    parser.add_argument("--degrees-per-frame", type=float, required=True,
                        help="the part's turn from one frame to the next")
    args = parser.parse_args()
    paths = sorted(glob.glob(args.frames))
    if len(paths) < 2:
        parser.error("%s: fewer than two frames" % args.frames)
    print("| frames | turn (degrees) | texture turned with it | left in place |")
    print("|---|---|---|---|")
    for k, (turn, with_it, left) in enumerate(measure(paths, args.degrees_per_frame)):
        print("| %d-%d | %.2f | %.3f | %.3f |" % (k, k + 1, turn, with_it, left))


if __name__ == "__main__":
    main()
