#!/usr/bin/env bash
# The pixel readout and the samples per pixel, in the real window under Xvfb
# (xdotool), read back from the viewer's event log (--edit-log) and an X
# screenshot:
#   O. three balls, one exact pass: the pointer at the image's right edge,
#      its bottom right corner and its left edge. The readout says
#      "1 sample"; its box stays inside the image (never over the panel,
#      never below the window), and the screenshot shows it there: dark
#      inside the box, the image just beside it.
#   M. 100 samples in one pass (a 512x128 wall, anti-aliased): the readout
#      says "100 samples", its widest line, and at the right edge its box
#      still ends left of the panel.
#   T. anti-aliasing, 2 samples a pass up to 6, the pointer moving over the
#      image all the while (frames drawn while a pass is half done): in
#      every frame the title's spp is the panel's; at the end the window's
#      title (from the X server) says 6 spp, as the panel's last frame.
# Exit 77 (ctest: skipped) without Xvfb, xdotool or xwd.
#   viewer_readout_window_test.sh path/to/whisker
set -u
. "$(dirname "$0")/viewer_drive.sh"
viewer_test_setup "$1" Xvfb xdotool xwd python3

cat >"$dir/cwd/wall.json" <<'INNER'
{"name": "wall",
 "camera": {"position": [0, 0, 55], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 60, "width": 512, "height": 128},
 "light": {"position": [0, 20, 40], "intensity": 2e10},
 "settings": {"spp": 100, "aa": true, "indirect": false, "target_spp": 100},
 "spheres": [{"name": "wall", "center": [0, 0, -1000], "radius": 900,
              "material": {"type": "diffuse", "albedo": [0.5, 0.6, 0.7]}}]}
INNER

cat >"$dir/drive.sh" <<'INNER'
# Hovers (x, y) in window units and waits for the readout of that pixel.
hover() {  # x y (image pixel = window position - the image's corner)
  local n
  n=$(grep -c '^readout ' "$log")
  xdotool mousemove --window "$wid" "$1" "$2"
  log_wait "len(readouts) > $n and readouts[-1]['lines'][0].startswith('pixel (%d, %d)' % ($1 - f['area'][0], $2 - f['area'][1]))" 30
}
O() {
  open_logged O "" || return
  log_wait "f['own_spp'] == 1 and f['shown_own'] == 1" 30
  hover 509 300; shot O-right
  hover 509 652; shot O-corner
  hover 2 150
  quit_viewer O
}
M() {
  open_logged M "--scene wall.json" || return
  log_wait "f['own_spp'] == 100 and f['shown_own'] == 100" 60
  hover 510 "$("$py" -c "import sys; sys.path.insert(0, '$tests'); import viewer_check as v; a = v.log_names(v.read_log('$log'))['f']['area']; print(a[1] + a[3] // 2)")"
  quit_viewer M
}
T() {
  open_viewer T "--aa on --spp 2 --target-spp 6 --edit-log $dir/T.log" || return
  log=$dir/T.log
  # The pointer goes to and fro over the image until the render is done.
  for k in $(seq 200); do
    xdotool mousemove --window "$wid" $(( 100 + (k % 20) * 15 )) 400; sleep 0.05
    log_has "f['own_spp'] == 6 and f['gen'] == f['own_gen']" && break
  done
  xdotool mousemove --window "$wid" 300 420; sleep 1
  xdotool getwindowname "$wid" >"$dir/T.title"
  quit_viewer T
}
O; M; T
INNER

in_xvfb

cat >"$dir/readout.py" <<'INNER'
import sys
sys.path.insert(0, sys.argv[1])
from viewer_check import crop, log_names, read_log, read_xwd
d, name, what = sys.argv[2], sys.argv[3], sys.argv[4]
names = log_names(read_log(f"{d}/{name}.log"))
rs, area = names["readouts"], names["f"].get("area", [0, 0, 0, 0])
if what == "inside":  # every readout box inside the image area
    ax, ay, aw, ah = area
    bad = [r for r in rs if not (r["box"][0] >= ax and r["box"][1] >= ay and
                                 r["box"][0] + r["box"][2] <= ax + aw and r["box"][1] + r["box"][3] <= ay + ah)]
    for r in rs:
        print("  box", r["box"], "|".join(r["lines"]))
    print(f"{len(rs)} readouts, {len(bad)} outside the image area {area}")
    sys.exit(0 if rs and not bad else 1)
if what == "says":  # every readout's last line starts with argv[5]
    lines = sorted(set(r["lines"][-1] for r in rs))
    print(lines)
    sys.exit(0 if rs and all(r["lines"][-1].startswith(sys.argv[5] + " (") for r in rs) else 1)
if what == "drawn":  # the screenshot argv[5] has the box of the readout of pixel argv[6]
    img = read_xwd(f"{d}/{sys.argv[5]}.xwd")
    r = [r for r in rs if r["lines"][0].startswith(f"pixel ({sys.argv[6]})")][-1]
    x, y, w, h = [int(round(v)) for v in r["box"]]
    inside = crop(img, x + 3, y + 3, w - 6, h - 6)[2]
    right = crop(img, x + w + 2, y, min(4, area[0] + area[2] - x - w - 2), h)[2]
    dark, beside = sum(inside) / len(inside), sum(right) / max(1, len(right))
    print(f"box {x},{y} {w}x{h}: mean level {dark:.1f} inside, {beside:.1f} just right of it")
    sys.exit(0 if dark < 50 and beside > dark + 20 else 1)
if what == "title":  # every frame: the title's spp is the panel's
    fs = names["frames"]
    differ = [f for f in fs if f["title_spp"] != f["panel_spp"]]
    seen = sorted(set(f["panel_spp"] for f in fs))
    print(f"{len(fs)} frames, spp seen {seen}, {len(differ)} where the title and the panel differ")
    for f in differ[:5]:
        print("  title", f["title_spp"], "panel", f["panel_spp"], "own", f["own_spp"])
    sys.exit(0 if fs and not differ and fs[-1]["panel_spp"] == 6 else 1)
INNER

r() { "$py" "$dir/readout.py" "$tests" "$dir" "$@"; }
for s in O M T; do echo "--- $s"; cat "$dir/$s.err"; done; cat "$dir/T.title"
check "every wait for the window was met in time" '[ ! -s "$dir/waits.err" ]'
check "O: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/O.err"'
check "O: at 1 spp the readout says \"1 sample\"" 'r O says "1 sample"'
check "O: at the right edge, the bottom right corner and the left edge the box stays over the image" 'r O inside'
check "O: the screenshot shows the box where the log says (right edge)" 'r O drawn O-right "509, 156"'
check "O: the screenshot shows the box where the log says (bottom right corner)" 'r O drawn O-corner "509, 508"'
check "M: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/M.err"'
check "M: at 100 spp the readout says \"100 samples\"" 'r M says "100 samples"'
check "M: its widest box still ends left of the panel" 'r M inside'
check "T: the viewer quit on Esc with exit 0" 'grep -q "^exit 0$" "$dir/T.err"'
check "T: in every frame the title and the panel say the same spp, 6 at the end" 'r T title'
check "T: the window's title says 6 spp" 'grep -q " 6 spp$" "$dir/T.title"'
exit $fail
