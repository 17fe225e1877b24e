#!/usr/bin/python3
"""Opens a page in headless Chromium as a person's browser would (scripts run, the live picture
streams) and checks what the screenshot shows. Used by the system tests of the operator's pages
(docs/web.md).

  page_screenshot.py URL PNG [--expect-colour R,G,B:MIN_PIXELS]... [--expect-text TEXT]...
                     [--docs-copy FILE]

Takes PNG (1100x1400 window, 6 s of the page's own time), then checks that the screenshot is a
picture, not a blank or broken page (many distinct colours), that each --expect-colour appears on
at least MIN_PIXELS pixels (within 30 per channel: e.g. the person box's green, the lines' yellow),
and that the page's text after its scripts ran (Chromium's DOM dump) holds each --expect-text.
--docs-copy writes a smaller copy of the screenshot for the docs (RTMOT_UPDATE_DOCS=1).
Exit 0 if all hold; 1 with the reason otherwise.
"""
import argparse
import html
import re
import subprocess
import sys

from PIL import Image, ImageChops

WINDOW = "1100,1400"
BUDGET_MS = "6000"  # the page's own clock: polls and MJPEG pictures within it, then the shot
COLOUR_TOLERANCE = 30
ATTEMPTS = 4
MIN_DISTINCT_COLOURS = 5000  # a camera picture has tens of thousands; a blank page a few dozen


def chromium(*arguments):
    # --no-sandbox: the tests run as root in CI, where Chromium's sandbox refuses to start.
    command = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
               "--window-size=" + WINDOW, "--virtual-time-budget=" + BUDGET_MS, *arguments]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        sys.exit("FAIL: chromium exited %d: %s" % (done.returncode, done.stderr[-2000:]))
    return done.stdout


def pixels_near(image, rgb):
    """How many pixels lie within COLOUR_TOLERANCE of rgb in every channel (PIL's C loops)."""
    masks = [band.point(lambda v, c=c: 255 if abs(v - c) <= COLOUR_TOLERANCE else 0)
             for band, c in zip(image.split(), rgb)]
    both = ImageChops.logical_and(masks[0].convert("1"), masks[1].convert("1"))
    return ImageChops.logical_and(both, masks[2].convert("1")).convert("L").histogram()[255]


def colour(text):
    rgb, _, count = text.partition(":")
    return tuple(int(c) for c in rgb.split(",")), int(count)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("url")
    parser.add_argument("png")
    parser.add_argument("--expect-colour", type=colour, action="append", default=[])
    parser.add_argument("--expect-text", action="append", default=[])
    parser.add_argument("--docs-copy")
    args = parser.parse_args()

    # The page is live: under a sanitizer the first tracks may reach the picture after the first
    # shot's budget, so a shot that lacks them is taken again, a few times, before failing.
    for attempt in range(1, ATTEMPTS + 1):
        chromium("--screenshot=" + args.png, args.url)
        image = Image.open(args.png).convert("RGB")
        distinct = len(image.getcolors(maxcolors=image.width * image.height))
        found = [pixels_near(image, want) for want, _ in args.expect_colour]
        problem = None
        if distinct < MIN_DISTINCT_COLOURS:
            problem = "the screenshot has %d colours: no picture on the page" % distinct
        for (want, least), n in zip(args.expect_colour, found):
            if n < least:
                problem = "%d pixels of colour %s in the screenshot, expected %d or more" % (
                    n, want, least)
        if problem is None:
            break
        if attempt == ATTEMPTS:
            sys.exit("FAIL: %s (%d shots)" % (problem, ATTEMPTS))

    text = html.unescape(re.sub(r"<[^>]*>", " ", chromium("--dump-dom", args.url)))
    text = " ".join(text.split())
    for want in args.expect_text:
        if want not in text:
            sys.exit("FAIL: the page does not say %r; it says: %s" % (want, text[:3000]))

    if args.docs_copy:
        # Cropped to what the page drew (not the window's empty margin), 3/4 size, 256 colours:
        # readable, and at a size a repository keeps.
        background = Image.new("RGB", image.size, image.getpixel((image.width - 1, image.height - 1)))
        page = image.crop(ImageChops.difference(image, background).getbbox() or (0, 0) + image.size)
        small = page.resize((page.width * 3 // 4, page.height * 3 // 4), Image.LANCZOS)
        small.quantize(colors=256).save(args.docs_copy, optimize=True)
    print("screenshot %s: %d colours; pixels of %s" % (args.png, distinct, ", ".join(
        "%s: %d" % (want, n) for (want, _), n in zip(args.expect_colour, found))))


if __name__ == "__main__":
    main()
