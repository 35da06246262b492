#!/usr/bin/env bash
# Runs tessera-render over every OBJ, PLY and glTF 2 model that ships with Assimp (Debian's
# assimp-testmodels) and prints, per file, OK or REJECTED with tessera-render's message.
# It fails (exit 1) when a run crashes (killed by a signal), hangs (60 s), exits 0 without
# writing the image or with anything on stderr, is rejected without exactly one line on stderr
# naming the file, or accepts a file that is broken on purpose. Exits 77 (ctest: skipped)
# when the models are not installed.
#
# usage: scripts/check-assimp-models.sh path/to/tessera-render [directory to keep the images]
# TESSERA_ASSIMP_MODELS overrides the models' directory (default /usr/share/assimp/models).
set -uo pipefail

if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 path/to/tessera-render [image directory]" >&2
  exit 2
fi
render=$1
models=${TESSERA_ASSIMP_MODELS:-/usr/share/assimp/models}

if [ ! -d "$models" ]; then
  echo "check-assimp-models: $models is missing (scripts/install-deps.sh installs" \
    "assimp-testmodels); skipped"
  exit 77
fi
if [ ! -x "$render" ]; then
  echo "check-assimp-models: $render is not an executable" >&2
  exit 2
fi

work=$(mktemp -d "${TMPDIR:-/tmp}/tessera-assimp-models.XXXXXX")
trap 'rm -rf "$work"' EXIT
images=${2:-$work/images}
mkdir -p "$images"

# Broken on purpose; accepting one of these is a failure.
known_broken() {
  case "$1" in
    glTF2/wrongTypes/* | glTF2/SchemaFailures/* | glTF2/IndexOutOfRange/* | *BoxWithInfinites*)
      return 0 ;;
  esac
  return 1
}

files=()
for sub in OBJ PLY glTF2; do
  if [ ! -d "$models/$sub" ]; then
    echo "FAIL     $sub: no such directory under $models"
    exit 1
  fi
done
while IFS= read -r -d '' f; do files+=("$f"); done < <(
  find "$models/OBJ" "$models/PLY" "$models/glTF2" -type f \
    \( -iname '*.obj' -o -iname '*.ply' -o -iname '*.gltf' -o -iname '*.glb' \) -print0 |
    sort -z)
if [ ${#files[@]} -eq 0 ]; then
  echo "FAIL     no .obj, .ply, .gltf or .glb files under $models"
  exit 1
fi

ok=0
rejected=0
failed=0
for file in "${files[@]}"; do
  rel=${file#"$models"/}
  image="$images/$(printf '%s' "$rel" | tr '/ ' '__').png"
  rm -f "$image"
  timeout 60 "$render" "$file" -o "$image" --width 320 --height 240 --samples 1 \
    >"$work/stdout" 2>"$work/stderr" </dev/null
  code=$?
  message=$(cat "$work/stderr")
  newlines=$(tr -cd '\n' <"$work/stderr" | wc -c)

  problem=""
  if [ $code -eq 124 ]; then
    problem="hung: killed after 60 s"
  elif [ $code -ge 128 ]; then
    problem="crashed: killed by signal $((code - 128))"
  elif [ $code -eq 0 ]; then
    if [ ! -s "$image" ]; then
      problem="exit 0 without writing $image"
    elif [ -n "$message" ]; then
      problem="exit 0 with output on stderr"
    elif known_broken "$rel"; then
      problem="accepted a file that is broken on purpose"
    fi
  elif [ -z "$message" ]; then
    problem="exit $code without a message"
  elif [ "$newlines" -ne 1 ]; then
    problem="exit $code with a message of $newlines lines"
  elif [[ "$message" != *"$(basename "$file")"* ]]; then
    problem="exit $code with a message that does not name the file"
  elif [ -e "$image" ]; then
    problem="exit $code but wrote $image"
  fi

  if [ -n "$problem" ]; then
    failed=$((failed + 1))
    echo "FAIL     $rel: $problem"
    [ -n "$message" ] && printf '%s\n' "$message" | sed 's/^/         | /'
  elif [ $code -eq 0 ]; then
    ok=$((ok + 1))
    echo "OK       $rel"
  else
    rejected=$((rejected + 1))
    echo "REJECTED $rel: ${message#tessera-render: }"
  fi
done

echo "check-assimp-models: ${#files[@]} files: $ok rendered, $rejected rejected, $failed failed"
[ $failed -eq 0 ]
