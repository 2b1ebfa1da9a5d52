#!/usr/bin/env bash
# Regenerate every picture in docs/img/ (those the README and the docs show), each by the command
# that makes it, from the current build (scripts/build.sh; the explorer's needs the web build,
# scripts/build-web.sh, and Chromium).
#
#   scripts/docs-images.sh           # all of them (the two studies take a few minutes)
#   scripts/docs-images.sh --quick   # without the bifurcation and lift-off studies
#
# default_accelerations.png, default_figure_eight.png  oscidrum run --plot (the default case)
# paper_fig22.png                                      oscidrum paper (Fig. 22)
# regularised_friction.png                             examples/regularised_friction.py
# explorer.png, explorer_vibratory.png                 scripts/screenshot-web.sh
# branch_*.png                                         scripts/bifurcation_study.py
# lift_off_maps.png                                    scripts/lift_off_study.py
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
[ "${1:-}" = "--quick" ] && quick=1
python=${OSCIDRUM_PYTHON:-/usr/bin/python3}
export PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}"
cli=build/apps/cli/oscidrum
[ -x "$cli" ] || { echo "docs-images: $cli not found: run scripts/build.sh first" >&2; exit 2; }
img=docs/img
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$cli" run --plot "$tmp/default" > /dev/null
cp "$tmp/default/accelerations.png" "$img/default_accelerations.png"
cp "$tmp/default/figure_eight.png" "$img/default_figure_eight.png"

"$cli" paper --out "$tmp/paper" > /dev/null
cp "$tmp/paper/fig22.png" "$img/paper_fig22.png"

"$python" examples/regularised_friction.py "$tmp/friction" > /dev/null
cp "$tmp/friction/regularised_friction.png" "$img/regularised_friction.png"

if [ -f web/dist/index.html ]; then
  scripts/screenshot-web.sh "" "$img/explorer.png"
  scripts/screenshot-web.sh "roller.type=vibratory" "$img/explorer_vibratory.png"
else
  echo "docs-images: web/dist missing (scripts/build-web.sh): explorer*.png left as they are" >&2
fi

if [ "$quick" = 0 ]; then
  "$python" scripts/bifurcation_study.py --cli "$cli" --out "$img" > /dev/null
  "$python" scripts/lift_off_study.py "$img" > /dev/null
fi
echo "docs-images: pictures in $img/ regenerated" >&2
