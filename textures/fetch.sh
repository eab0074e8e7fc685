#!/bin/sh
# Regenerates every file in textures/ from Debian packages (see textures/README.md for origin and licence).
# Run from the repository root: sh textures/fetch.sh (needs apt-get and oiiotool: openimageio-tools)
set -eu
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
apt-get download libirrlicht-doc cube2-data
dpkg-deb --fsys-tarfile libirrlicht-doc_*.deb | tar -x ./usr/share/doc/libirrlicht-dev/media/
dpkg-deb --fsys-tarfile cube2-data_*.deb | tar -x ./usr/share/games/cube2/packages/yo_frankie/
cd - >/dev/null
media="$tmp/usr/share/doc/libirrlicht-dev/media"
for f in lf rt ft bk; do
  cp "$media/irrlicht2_$f.jpg" textures/skybox/
done
# GL's cube-map convention wants the cap faces turned (found by matching face edges, see README.md)
oiiotool "$media/irrlicht2_up.jpg" --rotate90 -o textures/skybox/irrlicht2_up.jpg
oiiotool "$media/irrlicht2_dn.jpg" --rotate270 -o textures/skybox/irrlicht2_dn.jpg
cp "$tmp/usr/share/games/cube2/packages/yo_frankie/generic_grayrock1_col.jpg" textures/ground_rock.jpg
cp "$tmp/usr/share/games/cube2/packages/yo_frankie/generic_grass1_col.jpg" textures/ground_grass.jpg
cp "$tmp/usr/share/games/cube2/packages/yo_frankie/generic_dirt1_col.jpg" textures/ground_sand.jpg
