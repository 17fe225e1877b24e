#!/usr/bin/env bash
# System test: `cmake --install` into a DESTDIR with --prefix /usr gives a tree that runs by itself.
# The installed binary finds every OpenCV library it links inside the tree or in the system's
# library folders (never in the build tree: the pinned OpenCV is shipped in lib/rtmot, RUNPATH
# $ORIGIN/../lib/rtmot), answers --help, and tracks 12 frames of a test:// source with the
# installed model, from a folder outside the source tree, with a bare environment. The unit is
# written for the prefix used; only what a board needs is installed (no study).
# Usage: installed_tree_runs.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
stage=$work/stage
fail() { echo "FAIL: $*"; exit 1; }

DESTDIR=$stage cmake --install "$build" --prefix /usr >"$work/install.log" 2>&1 ||
  { cat "$work/install.log"; fail "cmake --install failed"; }
bin=$stage/usr/bin/rtmot
[[ -x $bin ]] || fail "no $bin"

# Every OpenCV library resolves inside the staged tree or the system's folders.
ldd "$bin" >"$work/ldd.txt" || fail "ldd $bin failed"
! grep -q "not found" "$work/ldd.txt" || { cat "$work/ldd.txt"; fail "a library is not found"; }
while read -r name _ path _; do
  path=$(readlink -f "$path")  # $ORIGIN/../lib/rtmot reads as .../usr/bin/../lib/rtmot
  case $path in
    "$stage"/usr/lib/*|/usr/lib/*|/lib/*) ;;
    *) fail "$name resolves to $path, outside the installed tree and the system" ;;
  esac
done < <(grep libopencv_ "$work/ldd.txt")
opencv_libs=$(grep -c libopencv_ "$work/ldd.txt" || true)
shipped=$(find "$stage/usr/lib" -maxdepth 3 -name 'libopencv_*.so.*' | wc -l)

cd "$work"  # not the source tree: nothing may be found relative to it
env -i PATH=/usr/bin:/bin "$bin" --help >"$work/help.txt" 2>&1 || { cat "$work/help.txt"; fail "--help failed"; }
grep -q "run" "$work/help.txt" || fail "--help lists no run command"

model=$stage/usr/share/rtmot/models/ssdlite_mobilenet_v2_coco.onnx
[[ -f $model ]] || fail "the model was not installed at $model (scripts/fetch_model.sh before the install)"
frames=12
# No --model: the installed rtmot finds its installed model.
env -i PATH=/usr/bin:/bin "$bin" run --source "test://ball?width=320&height=240" \
  --playback every-frame --max-frames $frames --jsonl "$work/tracks.jsonl" --report "$work/report.json" 2>"$work/run.err" ||
  { cat "$work/run.err"; fail "the installed rtmot run failed"; }
lines=$(wc -l <"$work/tracks.jsonl")
[[ $lines == "$frames" ]] || { cat "$work/run.err"; fail "$lines messages, expected $frames"; }

# A config file's relative paths start at its folder (run from /, elsewhere); `--config NAME`
# finds an installed config; a missing model says every place it was looked for.
mkdir -p "$work/board/configs" "$work/board/models"
cp "$(dirname "$model")"/* "$work/board/models/"  # the model, its anchors and checksums
printf 'detector:\n  kind: ssd\n  model: ../models/%s\nsource:\n  uri: "test://ball?width=320&height=240"\n' \
  "$(basename "$model")" >"$work/board/configs/board.yaml"
(cd / && env -i PATH=/usr/bin:/bin "$bin" run --config "$work/board/configs/board.yaml" \
  --playback every-frame --max-frames 3 2>"$work/board.err") ||
  { cat "$work/board.err"; fail "a config's relative model path did not resolve from its folder"; }
grep -q "($work/board/models/" "$work/board.err" || { cat "$work/board.err"; fail "not the config's model"; }
env -i PATH=/usr/bin:/bin "$bin" run --config desktop.yaml --source "test://ball?width=320&height=240" \
  --playback every-frame --max-frames 3 2>"$work/named.err" ||
  { cat "$work/named.err"; fail "--config desktop.yaml did not find the installed config"; }
status=0
env -i PATH=/usr/bin:/bin "$bin" run --model nothere.onnx --source "test://ball" --max-frames 1 \
  2>"$work/missing.err" || status=$?
[[ $status == 4 ]] || { cat "$work/missing.err"; fail "a missing model exited $status, expected 4"; }
grep -q "tried .*$stage/usr/share/rtmot/models/nothere.onnx" "$work/missing.err" ||
  { cat "$work/missing.err"; fail "the missing model's error does not say where it looked"; }

# The operator's page comes from the installed tree, not from the source tree the binary was built in.
for file in index.html app.js style.css listen.html listen.js; do
  [[ -f $stage/usr/share/rtmot/web/$file ]] || fail "the page's $file was not installed"
done
# A port chosen free may be taken before the run binds it, after its model loads: another port then
# (tests/system/background_run.sh's start_run_with_page does the same for the background runs).
for attempt in 1 2 3; do
  port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  env -i PATH=/usr/bin:/bin "$bin" run --source "test://ball?width=320&height=240" --playback every-frame \
    --max-frames 3 --web-port "$port" 2>"$work/web.err" && break
  grep -q "cannot listen (port in use?)" "$work/web.err" && [[ $attempt -lt 3 ]] && continue
  cat "$work/web.err"
  fail "a run with --web-port failed"
done
grep -q "web: the operator's page at http://127.0.0.1:$port/ (its files from $stage/usr/share/rtmot/web)" \
  "$work/web.err" || { cat "$work/web.err"; fail "the page's files were not the installed ones"; }
env -i PATH=/usr/bin:/bin "$bin" listen --port 0 --bind 127.0.0.1 --duration 0.5 --web-port "$port" \
  2>"$work/listen.err" >/dev/null || { cat "$work/listen.err"; fail "rtmot listen --web-port failed"; }
grep -q "web: the ground station's page at http://127.0.0.1:$port/ (its files from $stage/usr/share/rtmot/web)" \
  "$work/listen.err" || { cat "$work/listen.err"; fail "the ground station's page is not the installed one"; }

unit=$stage/usr/lib/systemd/system/rtmot.service
[[ -f $unit ]] || fail "no unit at $unit"
grep -qx "ExecStart=/usr/bin/rtmot run --config /usr/share/rtmot/configs/jetson-csi.yaml" "$unit" ||
  { grep -n "ExecStart\|/usr/local" "$unit"; fail "the unit does not name the /usr prefix"; }
! grep -q "/usr/local\|@" "$unit" || { grep -n "/usr/local\|@" "$unit"; fail "the unit names another prefix"; }
[[ -f $stage/usr/share/rtmot/configs/jetson-csi.yaml ]] || fail "the service's config is missing"
[[ -f $stage/usr/lib/sysusers.d/rtmot.conf ]] || fail "no sysusers file"
studied=$(find "$stage" -path '*study*' | head -n 3)
[[ -z $studied ]] || fail "research files installed: $studied"

echo "PASS: installed under DESTDIR with prefix /usr ($(du -sh "$stage" | cut -f1)); $opencv_libs OpenCV" \
  "libraries resolved ($shipped shipped in the tree); --help and a $frames-frame test:// run with the" \
  "installed model from $work; config-relative and installed paths found; unit ExecStart=/usr/bin/rtmot ... /usr/share/rtmot/configs/jetson-csi.yaml"
