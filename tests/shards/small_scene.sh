# Sourced by the shard script tests: small_scene OUT.json writes the indirect
# room at 96x96 with Fresnel glass and anti-aliasing, so parts go through
# splitting, the Fresnel choice and pixel jitter in a second or two.
small_scene() {
  python3 - "$WHISKER_SOURCE/assets/scenes/indirect.json" "$1" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["camera"].update(width=96, height=96)
scene["settings"].update(fresnel=True, aa=True)
json.dump(scene, open(sys.argv[2], "w"), indent=2)
PY
}
