"""The HTTP calls of tests/system/web_view.sh, as a browser makes them (standard library only).

Usage: web_client.py BASE_URL COMMAND [ARGS]
  status                     print /api/status (JSON)
  wait-processed N           wait until source 0 processed N frames (gives up after 300 s)
  jpeg                       read /video/0.mjpg until one whole JPEG arrived; print its size
  watchers-bounded MAX       once no watcher is counted, hold MAX streams open; the next one is
                             answered 503
  get PATH                   print "STATUS LENGTH" of a GET with the path sent as is
  post SOURCE TOKEN BODY     POST BODY to /api/events?source=SOURCE as the page does (TOKEN "-":
                             no Authorization header; BODY "@N": N bytes); print "STATUS JSON"
  wait-count NAME            wait until source 0's line NAME counted a crossing (300 s at most)
  wait-generation N          wait until source 0's counts are configuration N's (300 s at most):
                             the status switches at the first frame counted with it, not at the
                             save or the reload (docs/web.md)
  post-settings TOKEN BODY   POST BODY to /api/settings, as `post`; print "STATUS JSON"
"""
import http.client
import json
import sys
import time
import urllib.parse
import urllib.request

base = sys.argv[1]
command = sys.argv[2]
host = urllib.parse.urlparse(base)


def status():
    with urllib.request.urlopen(base + "api/status", timeout=60) as response:
        return json.load(response)


def open_stream():
    connection = http.client.HTTPConnection(host.hostname, host.port, timeout=120)
    connection.request("GET", "/video/0.mjpg")
    return connection, connection.getresponse()


def one_jpeg(response):
    """The first part of a multipart/x-mixed-replace stream: its headers, then Content-Length bytes."""
    kind = response.getheader("Content-Type")
    assert kind == "multipart/x-mixed-replace; boundary=frame", kind
    assert response.readline() == b"--frame\r\n"
    headers = {}
    while True:
        line = response.readline().decode().strip()
        if not line:
            break
        name, value = line.split(":", 1)
        headers[name.lower()] = value.strip()
    assert headers["content-type"] == "image/jpeg", headers
    body = response.read(int(headers["content-length"]))
    assert body[:2] == b"\xff\xd8" and body[-2:] == b"\xff\xd9", "not a whole JPEG"
    return body


if command == "status":
    print(json.dumps(status()))
elif command == "wait-processed":
    wanted = int(sys.argv[3])
    deadline = time.monotonic() + 300
    while status()["sources"][0]["frames_processed"] < wanted:
        if time.monotonic() > deadline:
            sys.exit("FAIL: frames were not processed")
        time.sleep(0.2)
elif command == "jpeg":
    connection, response = open_stream()
    assert response.status == 200, response.status
    print(len(one_jpeg(response)))
    connection.close()
elif command == "watchers-bounded":
    limit = int(sys.argv[3])
    # A client that went away holds its worker's watcher until that worker's next write fails (one
    # picture later, longer on a loaded machine): wait until nobody is counted, then fill the bound.
    deadline = time.time() + 120
    while sum(status()["watchers"]) > 0:
        assert time.time() < deadline, "watchers still counted 120 s after their clients left"
        time.sleep(0.1)
    held = []
    for _ in range(limit):
        connection, response = open_stream()
        assert response.status == 200, response.status
        one_jpeg(response)  # its worker is streaming
        held.append(connection)
    connection, response = open_stream()
    print(response.status)
    for c in held + [connection]:
        c.close()
elif command == "get":
    connection = http.client.HTTPConnection(host.hostname, host.port, timeout=60)
    connection.putrequest("GET", sys.argv[3], skip_host=False, skip_accept_encoding=True)
    connection.endheaders()
    response = connection.getresponse()
    body = response.read()
    print(response.status, len(body), b"cmake_minimum_required" in body)
elif command in ("post", "post-settings"):
    if command == "post":
        source, token, body = sys.argv[3], sys.argv[4], sys.argv[5]
        path = "/api/events?source=" + source
    else:
        token, body = sys.argv[3], sys.argv[4]
        path = "/api/settings"
    data = (b"x" * int(body[1:])) if body.startswith("@") else body.encode()
    headers = {"Content-Type": "application/json"}
    if token != "-":
        headers["Authorization"] = "Bearer " + token
    connection = http.client.HTTPConnection(host.hostname, host.port, timeout=60)
    try:
        connection.request("POST", path, body=data, headers=headers)
        response = connection.getresponse()
        print(response.status, response.read().decode())
    except (BrokenPipeError, ConnectionResetError):
        # The server answers an oversize body at once and closes; what it said may be lost.
        print(0, "{}")
elif command == "wait-count":
    name = sys.argv[3]
    deadline = time.monotonic() + 300
    while True:
        lines = {l["name"]: l for l in status()["events"][0]["lines"]}
        if name in lines and lines[name]["in"] + lines[name]["out"] > 0:
            print(json.dumps(lines[name]))
            break
        if time.monotonic() > deadline:
            sys.exit("FAIL: line %s counted nothing" % name)
        time.sleep(0.2)
elif command == "wait-generation":
    wanted = int(sys.argv[3])
    deadline = time.monotonic() + 300
    while status()["events"][0]["generation"] != wanted:
        if time.monotonic() > deadline:
            sys.exit("FAIL: the counts are not configuration %d's" % wanted)
        time.sleep(0.2)
else:
    sys.exit("unknown command " + command)
