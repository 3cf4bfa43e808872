# Shared by judge.sh and contact-sheet.sh: where things are, and rendering one
# eval scene (../shared/eval/scenes, framed like the real clips: one flame on
# black) headless at 256x256, 60 fps.
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${CANDELA_BUILD_DIR:-$root/build}
candela=${CANDELA:-$build/firmware/candela}
tool=${CANDELA_TOOL:-$build/tools/candela-tool/candela-tool}
eval_dir=${CANDELA_EVAL_DIR:-$root/../shared/eval}
flames=${CANDELA_FLAMES_DIR:-$root/../shared/data/flames}
frames=${FRAMES:-600}

need_tools() {
  for b in "$candela" "$tool"; do
    [ -x "$b" ] || { echo "$b: not built (cmake --build build --target candela candela-tool)" >&2; exit 2; }
  done
}

need_shared() {
  if [ ! -d "$eval_dir/scenes" ] || [ ! -d "$flames" ]; then
    echo "skipped: the shared eval scenes ($eval_dir/scenes) or clips ($flames) are not here" >&2
    exit 77
  fi
  need_tools
}

# scene_file NAME: a path, or an eval scene by name (a_candle_calm) or letter (a).
scene_file() {
  if [ -f "$1" ]; then echo "$1"; return; fi
  local f
  for f in "$eval_dir/scenes/$1.toml" "$eval_dir/scenes/$1"_*.toml; do
    [ -f "$f" ] && { echo "$f"; return; }
  done
  echo "no scene '$1' (a file, or one of: $(cd "$eval_dir/scenes" && ls | sed 's/\.toml$//' | tr '\n' ' '))" >&2
  exit 2
}

# render SCENE_FILE SEED OUT_DIR
render() {
  mkdir -p "$3"
  if ! "$candela" --display headless --size 256x256 --frames "$frames" --seed "$2" \
      --scene "$1" --out "$3/" >"$3.log" 2>&1; then
    echo "rendering $1 failed:" >&2
    tail -5 "$3.log" >&2
    exit 2
  fi
}
