"""The HTTP calls and the screenshot check of tests/system/listen_web_view.sh (PIL besides the
standard library).

Usage: listen_web_client.py BASE_URL COMMAND [ARGS]
  ready IDS                  whether /api/listen shows each stream of IDS (comma-separated) with
                             tracks and a 768x576 frame: exit 0 and print the JSON, or exit 1
  status METHOD PATH         print the status of METHOD PATH, the path sent as is (0: no answer)
  big-head BYTES             send a GET whose head is BYTES long; print the status (0: no answer)
  screenshot FILE IDS        check a screenshot of the page: a canvas per stream of IDS, each with
                             boxes drawn in the tracks' colour (listen.js)
  crop IN OUT                IN without the empty page below and right of its content, as OUT
"""
import http.client
import json
import socket
import sys
import urllib.parse
import urllib.request

base = sys.argv[1]
command = sys.argv[2]
host = urllib.parse.urlparse(base)

# listen.js's colours.
TRACK = (0x00, 0xFF, 0x66)
BACKGROUND = (0x1C, 0x28, 0x33)
PAGE = (0xF4, 0xF4, 0xF4)  # style.css's body


def listen():
    with urllib.request.urlopen(base + "api/listen", timeout=60) as response:
        return json.load(response)


def near(pixel, colour, tolerance):
    return all(abs(a - b) <= tolerance for a, b in zip(pixel[:3], colour))


def runs(counts, least):
    """Runs of consecutive indexes whose count is at least `least`: [(start, end)]."""
    found, start = [], None
    for i, count in enumerate(counts + [0]):
        if count >= least and start is None:
            start = i
        elif count < least and start is not None:
            found.append((start, i))
            start = None
    return found


if command == "ready":
    wanted = {int(i) for i in sys.argv[3].split(",")}
    page = listen()
    ready = {s["stream"] for s in page["streams"]
             if s["tracks"] and s["width"] == 768 and s["height"] == 576}
    print(json.dumps(page))
    sys.exit(0 if wanted <= ready else 1)
elif command == "status":
    connection = http.client.HTTPConnection(host.hostname, host.port, timeout=60)
    try:
        connection.putrequest(sys.argv[3], sys.argv[4], skip_host=False, skip_accept_encoding=True)
        connection.putheader("Content-Length", "2")
        connection.endheaders(b"{}")
        response = connection.getresponse()
        body = response.read()
        print(response.status, b"cmake_minimum_required" in body)
    except (BrokenPipeError, ConnectionResetError, http.client.RemoteDisconnected):
        print(0, False)
elif command == "big-head":
    size = int(sys.argv[3])
    head = b"GET / HTTP/1.1\r\nHost: x\r\nX-Padding: "
    head += b"a" * (size - len(head) - 4) + b"\r\n\r\n"
    with socket.create_connection((host.hostname, host.port), timeout=60) as s:
        try:
            s.sendall(head)
            answer = s.recv(64)
        except (BrokenPipeError, ConnectionResetError):
            answer = b""
    print(int(answer.split()[1]) if answer.startswith(b"HTTP/") else 0)
elif command == "screenshot":
    from PIL import Image
    image = Image.open(sys.argv[3]).convert("RGB")
    width, height = image.size
    data = list(image.getdata())  # row by row
    background = [near(p, BACKGROUND, 2) for p in data]
    track = [near(p, TRACK, 40) for p in data]
    wanted = len(sys.argv[4].split(","))

    def count(mask, x0, y0, x1, y1):
        return sum(sum(mask[y * width + x0:y * width + x1]) for y in range(y0, y1))

    # The canvases: rectangles of listen.js's background, found as runs of columns (side by side)
    # or of rows (one above the other) rich in it.
    columns = [sum(background[x::width]) for x in range(width)]
    rows = [sum(background[y * width:(y + 1) * width]) for y in range(height)]
    across = [r for r in runs(columns, 120) if r[1] - r[0] >= 200]
    down = [r for r in runs(rows, 120) if r[1] - r[0] >= 150]
    if len(across) >= wanted:
        regions = [(x0, 0, x1, height) for x0, x1 in across]
    elif len(down) >= wanted:
        regions = [(0, y0, width, y1) for y0, y1 in down]
    else:
        sys.exit("FAIL: %d canvases in the screenshot, %d wanted (columns %s, rows %s)"
                 % (max(len(across), len(down)), wanted, across, down))
    for x0, y0, x1, y1 in regions:
        canvas = count(background, x0, y0, x1, y1)
        boxes = count(track, x0, y0, x1, y1)
        print("canvas at x %d-%d, y %d-%d: %d background pixels, %d box pixels"
              % (x0, x1, y0, y1, canvas, boxes))
        if canvas < 100000:
            sys.exit("FAIL: a canvas of %d pixels: not drawn at its frame size" % canvas)
        if boxes < 200:
            sys.exit("FAIL: a canvas without boxes (%d pixels of the tracks' colour)" % boxes)
elif command == "crop":
    from PIL import Image, ImageChops
    image = Image.open(sys.argv[3]).convert("RGB")
    page = Image.new("RGB", image.size, PAGE)
    box = ImageChops.difference(image, page).getbbox() or (0, 0) + image.size
    image.crop((0, 0, min(image.width, box[2] + 16), min(image.height, box[3] + 16))).save(
        sys.argv[4], optimize=True)
else:
    sys.exit("unknown command " + command)
