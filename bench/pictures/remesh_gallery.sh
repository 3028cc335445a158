#!/usr/bin/env bash
# Pictures of every remeshing scheme on real meshes (issue 18): runs
# `holey remesh --scheme S` for each scheme listed by `holey remesh --help`
# on spot's quad cage (160 quads, 16 pentagons, 4 triangles) and on the
# closed triangle mesh spot_triangulated.obj, renders each result with
# `holey render`, and writes the pictures with an index.html into OUT.
#
#   bench/pictures/remesh_gallery.sh [OUT] [HOLEY]
#
# OUT defaults to /tmp/holey-gallery (never the repository); HOLEY to the
# release binary of $CARGO_TARGET_DIR (or target/). A scheme a mesh
# refuses (the dual-based ones need a closed surface) is listed with its
# message instead of a picture. Meshes come from ../shared/data/meshes
# (see its README); HOLEY_MESHES overrides the directory.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
out="${1:-/tmp/holey-gallery}"
holey="${2:-${CARGO_TARGET_DIR:-$repo/target}/release/holey}"
meshes="${HOLEY_MESHES:-$repo/../shared/data/meshes}"

case "$(realpath -m "$out")/" in
"$repo"/*) echo "refusing to write into the repository: $out" >&2; exit 2 ;;
esac
[ -x "$holey" ] || { echo "no holey binary at $holey (build with cargo build --release -p holey-cli)" >&2; exit 2; }

# The scheme names, from the CLI's own list (indented lines of --help
# between "Schemes" and the first blank line).
mapfile -t schemes < <("$holey" remesh --help |
    awk '/^Schemes/ {on = 1; next} on && /^$/ {exit} on && /^  [a-z0-9]/ {print $1}')
[ "${#schemes[@]}" -gt 0 ] || { echo "no schemes in holey remesh --help" >&2; exit 2; }

mkdir -p "$out"
index="$out/index.html"
{
    echo '<!doctype html><meta charset="utf-8"><title>holey remesh gallery</title>'
    echo '<style>body{font-family:sans-serif}figure{display:inline-block;margin:4px}img{width:400px}figcaption{font-size:13px}</style>'
} > "$index"

# name, file, render options
cases=(
    "spot-cage|$meshes/spot_control_mesh.obj|--up y --view 1,0.3,1"
    "spot-tri|$meshes/spot_triangulated.obj|--up y --view 1,0.3,1"
)
for entry in "${cases[@]}"; do
    IFS='|' read -r name file view <<< "$entry"
    dir="$out/$name"
    mkdir -p "$dir"
    echo "<h2>$name ($(basename "$file"))</h2>" >> "$index"
    # shellcheck disable=SC2086
    "$holey" render "$file" "$dir/input.png" $view --edges
    echo "<figure><img src=\"$name/input.png\"><figcaption>input</figcaption></figure>" >> "$index"
    for s in "${schemes[@]}"; do
        obj="$dir/$s.obj"
        # Global extrusion's default distance (2, TopMod's) is absolute and
        # dwarfs spot (about 1 unit across): a tenth of spot's edge length.
        extra=()
        case "$s" in
        global-extrude | dual-global-extrude) extra=(--length 0.02) ;;
        esac
        if msg=$("$holey" remesh "$file" "$obj" --scheme "$s" "${extra[@]}" 2>&1); then
            # shellcheck disable=SC2086
            "$holey" render "$obj" "$dir/$s.png" $view --edges
            info=$("$holey" info "$obj" | awk '/^(vertices|edges|genus):/ {printf "%s %s  ", $1, $2}')
            echo "<figure><img src=\"$name/$s.png\"><figcaption>$s: $info</figcaption></figure>" >> "$index"
            echo "$name $s: $info"
        else
            echo "<p>$s refused: $(echo "$msg" | sed 's/&/\&amp;/g; s/</\&lt;/g')</p>" >> "$index"
            echo "$name $s: refused: $msg"
        fi
    done
done
echo "wrote $index"
