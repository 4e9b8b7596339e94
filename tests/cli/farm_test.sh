# Recording as render farms do: frame sets (1-100, 0-119:10, 1,5,10-20,
# A:B), output patterns (shot_####.png), resuming an interrupted recording,
# and shards (--shard i/n, interleaved) whose union equals one local record
# byte for byte, driven by examples/slurm/record_array.sh with the array
# variables Slurm would set (a real one-node cluster is not started here).
source "$(dirname "$0")/lib.sh"
SCENE=tests/scenes/deform.lua
files() { (cd "$1" && ls | tr '\n' ' '); }

"$CAUSTICA" record $SCENE -o "$WORK/steps/s_##.png" --frames 0-9:3 --size 24x24 >/dev/null
[ "$(files "$WORK/steps")" = "s_00.png s_03.png s_06.png s_09.png " ] && pass "0-9:3 into s_##.png" \
  || fail "a stepped range into a pattern" "$(files "$WORK/steps")"
"$CAUSTICA" record $SCENE -o "$WORK/list" --frames 1,5,3-4,5 --size 24x24 >/dev/null
[ "$(files "$WORK/list")" = "frame_0001.png frame_0003.png frame_0004.png frame_0005.png " ] \
  && pass "1,5,3-4,5: each frame once, into a folder" || fail "a list" "$(files "$WORK/list")"
"$CAUSTICA" record $SCENE -o "$WORK/old" --frames 2:3 --size 24x24 >/dev/null
[ "$(files "$WORK/old")" = "frame_0002.png frame_0003.png " ] && pass "A:B still inclusive" \
  || fail "A:B" "$(files "$WORK/old")"
"$CAUSTICA" record $SCENE -o "$WORK/pfm/f_####.pfm" --frames 4 --size 24x24 >/dev/null
[ "$(files "$WORK/pfm")" = "f_0000.pfm f_0001.pfm f_0002.pfm f_0003.pfm " ] && pass "a count, as PFM" \
  || fail "a count as PFM" "$(files "$WORK/pfm")"
expect_error "a backwards range" 2 "--frames: '5-3' runs backwards" - -- \
  "$CAUSTICA" record $SCENE -o "$WORK/bad" --frames 5-3
expect_error "a step of 0" 2 "runs backwards or has a step below 1" - -- \
  "$CAUSTICA" record $SCENE -o "$WORK/bad" --frames 0-9:0
expect_error "not a frame" 2 "--frames: 'x' is not a frame" - -- \
  "$CAUSTICA" record $SCENE -o "$WORK/bad" --frames 1,x
expect_error "a bad shard" 2 "--shard needs i/n" - -- "$CAUSTICA" record $SCENE -o "$WORK/bad" --shard 4/4
expect_error "# in a folder" 2 "the # run must be in the file name" - -- \
  "$CAUSTICA" record $SCENE -o "$WORK/d_##/f.png"
expect_error "a pattern's type" 2 "must end in .png, .jpg, .tif, .pfm, .hdr or .exr" - -- \
  "$CAUSTICA" record $SCENE -o "$WORK/f_##.bmp"

# Resume: the frames on disk are kept, the missing one rendered; --overwrite renders all.
"$CAUSTICA" record $SCENE -o "$WORK/resume" --frames 0-5 --size 24x24 >/dev/null
cp "$WORK/resume/frame_0002.png" "$WORK/kept.png"
rm "$WORK/resume/frame_0003.png"
touch -d '2000-01-01' "$WORK/resume/frame_0002.png"
out=$("$CAUSTICA" record $SCENE -o "$WORK/resume" --frames 0-5 --size 24x24)
grep -q "wrote 1 frame: .*frame_0003.png" <<<"$out" && grep -q "skipped 5 frames already written" <<<"$out" \
  && [ "$(find "$WORK/resume" -name frame_0002.png -newer "$WORK/kept.png" | wc -l)" = 0 ] \
  && pass "a second run renders only the missing frame" || fail "resume" "$out"
out=$("$CAUSTICA" record $SCENE -o "$WORK/resume" --frames 0-5 --size 24x24 --overwrite)
grep -q "wrote 6 frames" <<<"$out" && pass "--overwrite renders them again" || fail "--overwrite" "$out"

# Shards: an array job of 4 tasks over 8 frames equals one local record.
"$CAUSTICA" record $SCENE -o "$WORK/local" --frames 0-7 --size 24x24 >/dev/null
for i in 0 1 2 3; do
  SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=4 CAUSTICA="$CAUSTICA" CAUSTICA_SIZE=24x24 \
    bash examples/slurm/record_array.sh $SCENE "$WORK/farm" 0-7 >"$WORK/task$i.log" 2>&1 \
    || fail "array task $i" "$(cat "$WORK/task$i.log")"
done
grep -q "frame_0001.png .. .*frame_0005.png" "$WORK/task1.log" && pass "shard 1/4 renders frames 1 and 5 (interleaved)" \
  || fail "shard 1/4" "$(cat "$WORK/task1.log")"
same=0
for f in "$WORK"/local/*.png; do cmp -s "$f" "$WORK/farm/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 8 ] && [ "$(ls "$WORK/farm" | wc -l)" = 8 ] && pass "4 shards == one local record, byte for byte" \
  || fail "shards" "$same of 8 equal; farm holds: $(files "$WORK/farm")"
expect_error "the array script outside Slurm" 1 "not inside a Slurm array job" - -- \
  env -u SLURM_ARRAY_TASK_ID bash examples/slurm/record_array.sh $SCENE "$WORK/farm2"
# Video previews: ffmpeg missing is one clear line naming the package (the frames stay on disk);
# with an ffmpeg on PATH (here a stand-in that records how it is called) every frame is handed to it in order.
expect_error "no ffmpeg" 1 "ffmpeg is not installed (apt-get install ffmpeg); the frames are on disk" - -- \
  env PATH=/nonexistent "$CAUSTICA" record $SCENE -o "$WORK/vid" --frames 0-2 --size 24x24 --video "$WORK/v.mp4"
[ "$(ls "$WORK/vid" | wc -l)" = 3 ] && pass "the frames stay without ffmpeg" || fail "frames without ffmpeg" "$(ls "$WORK/vid")"
mkdir -p "$WORK/fakebin"
cat >"$WORK/fakebin/ffmpeg" <<'SH'
#!/bin/sh
# records its arguments and the numbered sequence it was given (each link and where it points)
for a in "$@"; do case "$a" in *%08d.png) dir=$(dirname "$a");; esac; done
for f in "$dir"/*.png; do echo "$(basename "$f") $(readlink "$f")"; done >"$FAKE_LOG.list"
echo "$@" >"$FAKE_LOG"
for last in "$@"; do :; done
echo video >"$last"
SH
cat >"$WORK/fakebin/ffprobe" <<'SH'
#!/bin/sh
# the frames a real encode of the recorded sequence would hold
wc -l <"$FAKE_LOG.list"
SH
chmod +x "$WORK/fakebin/ffmpeg" "$WORK/fakebin/ffprobe"
FAKE_LOG="$WORK/ffmpeg.log" PATH="$WORK/fakebin:$PATH" "$CAUSTICA" record $SCENE -o "$WORK/vid" --frames 0-2 --size 24x24 \
  --video "$WORK/v.mp4" >"$WORK/video.txt" 2>&1
grep -q "wrote $WORK/v.mp4 (3 frames at" "$WORK/video.txt" && [ "$(cat "$WORK/v.mp4")" = video ] \
  && grep -q -- "-framerate 30 -start_number 0 -f image2 -i $WORK/\.v\.mp4\.caustica-tmp\.[0-9]*\.[A-Za-z0-9]*/%08d\.png .*pad=ceil(iw/2)\*2:ceil(ih/2)\*2 .*-crf 18 -pix_fmt yuv420p .*-color_trc iec61966-2-1 .* $WORK/\.v\.mp4\.caustica-tmp\.[0-9]*\.[A-Za-z0-9]*/video\.mp4" "$WORK/ffmpeg.log" \
  && [ "$(grep -c "^0000000[0-2].png .*/frame_000[0-2].png$" "$WORK/ffmpeg.log.list")" = 3 ] \
  && [ "$(sed -n 's/^0*\([0-9]\)\.png .*frame_000\([0-9]\)\.png$/\1\2/p' "$WORK/ffmpeg.log.list" | tr '\n' ' ')" = "00 11 22 " ] \
  && pass "--video hands every frame to ffmpeg in order as one numbered sequence (padded to even sizes, tagged sRGB, through a temporary)" \
  || fail "--video" "$(cat "$WORK/video.txt" "$WORK/ffmpeg.log" "$WORK/ffmpeg.log.list" 2>&1)"
if command -v ffmpeg >/dev/null; then
  "$CAUSTICA" record $SCENE -o "$WORK/vid" --frames 0-2 --size 24x24 --video "$WORK/real.gif" >/dev/null 2>&1 \
    && [ -s "$WORK/real.gif" ] && pass "ffmpeg encodes a GIF" || fail "ffmpeg GIF" "no file"
  # an odd size: libx264's 4:2:0 needs even ones, so the frames are padded by a pixel
  "$CAUSTICA" record $SCENE -o "$WORK/odd" --frames 0-2 --size 33x33 --video "$WORK/odd.mp4" >/dev/null 2>"$WORK/odd.err"
  if command -v ffprobe >/dev/null; then
    probe=$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height,color_primaries,color_transfer \
      -of csv=p=0 "$WORK/odd.mp4" 2>&1)
    [ "$probe" = "34,34,iec61966-2-1,bt709" ] && ! ls "$WORK"/.odd.mp4* >/dev/null 2>&1 \
      && pass "a 33x33 recording encodes as 34x34 H.264 tagged BT.709 / sRGB, no temporary left" \
      || fail "odd-size video" "$probe $(cat "$WORK/odd.err")"
  else
    [ -s "$WORK/odd.mp4" ] && pass "a 33x33 recording encodes" || fail "odd-size video" "$(cat "$WORK/odd.err")"
  fi
fi
finish
