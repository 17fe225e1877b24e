# shellcheck shell=bash
# Sourced by the system tests that need a folder of still images cut from a video.
#   cut_video_into_images VIDEO FOLDER COUNT   -> FOLDER/000001.jpg .. COUNT, or a failure named
# This machine's gst-launch-1.0 with this machine's plugins: the cross stage points GStreamer's
# variables at the arm64 sysroot's plugin set (scripts/cross_env.sh), which only rtmot under qemu
# reads; a test's own tools must not load them (two tests failed there, one round apart, each with
# its own copy of this pipeline).
cut_video_into_images() {
  local video=$1 folder=$2 count=$3
  mkdir -p "$folder"
  env -u GST_REGISTRY -u GST_REGISTRY_UPDATE -u GST_REGISTRY_FORK -u GST_PLUGIN_SYSTEM_PATH \
    -u GST_PLUGIN_PATH gst-launch-1.0 -q filesrc location="$video" ! decodebin \
    ! identity eos-after=$((count + 4)) ! videoconvert ! jpegenc \
    ! multifilesink location="$folder/%06d.jpg" index=1 >/dev/null 2>&1 ||
    { echo "FAIL: gst-launch-1.0 could not cut $video into images"; return 1; }
  # identity's EOS races the last buffers into the sink (eos-after=12 gave 11 or 12 images, seen in
  # 2 of 8 runs): cut a few more and keep the first COUNT.
  find "$folder" -name '*.jpg' | LC_ALL=C sort | tail -n +$((count + 1)) | xargs -r rm --
  local cut
  cut=$(find "$folder" -name '*.jpg' | wc -l)
  [[ $cut == "$count" ]] || { echo "FAIL: $count images expected from $video, cut $cut"; return 1; }
}
