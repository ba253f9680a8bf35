#!/usr/bin/env bash
# Regenerate the gallery of `facetlab render` pictures in results/gallery/ (run from anywhere):
#   bash results/gallery/make.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
out=results/gallery
render() { cargo run --quiet --release -- render "$@" --force --quiet; }

render tolkowsky --light iso --size 360 -o "$out/tolkowsky-iso.png"
render tolkowsky --light cos --head-shadow 15 --size 360 -o "$out/tolkowsky-cos-head15.png"
render tolkowsky princess emerald --light aset --size 280 -o "$out/aset-round-princess-emerald.png" \
    --json "$out/aset-round-princess-emerald.json"
render tolkowsky --light fire --exposure 3 --size 360 -o "$out/tolkowsky-fire.png"
render tolkowsky --light hearts --size 320 -o "$out/tolkowsky-hearts.png"
render tolkowsky --light arrows --size 320 -o "$out/tolkowsky-arrows.png"
render tolkowsky gia-reference --light idealscope --size 320 -o "$out/idealscope-tolkowsky-gia.png"
render tolkowsky --light iso --tilt 20 --size 360 -o "$out/tolkowsky-iso-tilt20.png"
render tolkowsky --light cos --head-shadow 15 --rock 15:8 --size 180 -o "$out/tolkowsky-cos-rock.png"
render tolkowsky --material tourmaline --colour "#1f5a36@10mm" --diameter-mm 9 --set pavilion_angle=43 \
    --light cos --head-shadow 15 --size 320 -o "$out/tourmaline-dark-cos.png"
render tolkowsky --material beryl --colour "#bfe0ea@10mm" --diameter-mm 8 \
    --light cos --head-shadow 15 --size 320 -o "$out/aquamarine-pale-cos.png"
# Pleochroism: a ruby with its c-axis ⟂ the table (the purplish-red E⊥c ray face-up) and in
# the table's plane (more of the lighter, orange-red E∥c ray).
render oval --material ruby --optic-axis 0 --light cos --head-shadow 15 --size 320 -o "$out/ruby-oval-axis0-cos.png"
render oval --material ruby --optic-axis 90 --light cos --head-shadow 15 --size 320 -o "$out/ruby-oval-axis90-cos.png"
# Photographs (`--light` a studio rig or the procedural studio map; `--view`, `--ground`).
render tolkowsky --light tent --view 30 --size 420 -o "$out/photo-tolkowsky-tent.png"
render princess --light darkfield --view 45 --size 420 -o "$out/photo-princess-darkfield.png"
render oval --material blue-sapphire --diameter-mm 7 --light daylight --ground white --view 35 \
    --exposure 0.45 --size 420 -o "$out/photo-sapphire-daylight.png"
render tolkowsky --light studio --view 8 --ground white --size 420 -o "$out/photo-tolkowsky-side.png"
# `facetlab plan`: the best round brilliant in the example rough, three views.
plan_dir=$(mktemp -d)
cargo run --quiet --release -- plan cuts/rough-octahedron.obj --family round-brilliant --top 1 --quiet -o "$plan_dir/run"
cp "$plan_dir/run/round-brilliant-1-views.png" "$out/plan-rough-octahedron.png"
rm -r "$plan_dir"
ls -l "$out"
