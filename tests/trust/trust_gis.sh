#!/bin/sh
# A stranger's DEM, imagery, vectors or track is data: it never makes fathom connect anywhere, nor read a
# file the user did not name (outside the folders of the files named, a device, a FIFO, standard input).
# Every entry point that opens a GIS file (a shot's --dem, terrain.imagery, terrain.vectors, fathom
# viewshed, fathom track, fathom mesh --dem, fathom water, terrain.water) meets each driver family's attack; a loopback listener
# counts the connections each case makes (issue 50, items 1-2: 1-18 connections a file before).
# Usage: trust_gis.sh FATHOM SRC LISTEN_COUNT
fathom=$1
src=$2
listen=$3
. "$src/tests/lib/trust_lib.sh"
extra_cleanup='kill "$lpid" 2>/dev/null'

"$listen" "$tmp/port" "$tmp/count" 3600 &
lpid=$!
i=0
while [ ! -s "$tmp/port" ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
port=$(cat "$tmp/port")
[ -n "$port" ] || { echo "FAIL the listener did not start"; exit 1; }
url="http://127.0.0.1:$port"

mkdir "$tmp/evil" "$tmp/elsewhere" "$tmp/out"
cp "$src/terrains/himalaya.tif" "$tmp/evil/dem.tif"
cp "$src/terrains/himalaya.tif" "$tmp/elsewhere/dem.tif"
printf 'root:x:0:0:FAKESECRET:/root:/bin/bash\n%.0s' $(seq 1 400) >"$tmp/elsewhere/secret.txt"
mkfifo "$tmp/evil/fifo.tif"
e=$tmp/evil

# a raster VRT around one source (the source's text as given)
vrt() {
    printf '<VRTDataset rasterXSize="241" rasterYSize="145"><SRS>EPSG:4326</SRS>'
    printf '<GeoTransform>84,0.0417,0,32,0,-0.0417</GeoTransform>'
    printf '<VRTRasterBand dataType="Int16" band="1"><SimpleSource><SourceFilename relativeToVRT="%s">%s' "$2" "$1"
    printf '</SourceFilename><SourceBand>1</SourceBand></SimpleSource></VRTRasterBand></VRTDataset>\n'
}
vrt "$url/dem.tif" 0 >"$e/http.vrt"
vrt "/vsicurl/$url/dem.tif" 0 >"$e/vsicurl.vrt"
vrt "WMS:$url/wms?SERVICE=WMS" 0 >"$e/wmsconn.vrt"
vrt "$tmp/elsewhere/dem.tif" 0 >"$e/outside.vrt"
vrt "../elsewhere/dem.tif" 1 >"$e/updir.vrt"
vrt "/dev/stdin" 0 >"$e/stdin.vrt"
vrt "/vsistdin/" 0 >"$e/vsistdin.vrt"
vrt "fifo.tif" 1 >"$e/fifo.vrt"
vrt "/proc/self/environ" 0 >"$e/proc.vrt"
vrt "dem.tif" 1 >"$e/inside.vrt" # the control: a mosaic of the folder's own file opens
printf '<GDAL_WMS><Service name="WMS"><ServerUrl>%s/wms?</ServerUrl><Layers>x</Layers></Service><DataWindow>' "$url" >"$e/wms.xml"
printf '<UpperLeftX>84</UpperLeftX><UpperLeftY>32</UpperLeftY><LowerRightX>94</LowerRightX><LowerRightY>26</LowerRightY>' >>"$e/wms.xml"
printf '<SizeX>241</SizeX><SizeY>145</SizeY></DataWindow><Projection>EPSG:4326</Projection></GDAL_WMS>\n' >>"$e/wms.xml"
printf '<WCS_GDAL><ServiceURL>%s/wcs?</ServiceURL><CoverageName>x</CoverageName></WCS_GDAL>\n' "$url" >"$e/wcs.xml"
printf '<GDAL_WMS><Service name="TMS"><ServerUrl>%s/${z}/${x}/${y}.png</ServerUrl></Service><DataWindow>' "$url" >"$e/tms.xml"
printf '<UpperLeftX>-20037508.34</UpperLeftX><UpperLeftY>20037508.34</UpperLeftY><LowerRightX>20037508.34</LowerRightX>' >>"$e/tms.xml"
printf '<LowerRightY>-20037508.34</LowerRightY><TileLevel>18</TileLevel><TileCountX>1</TileCountX><TileCountY>1</TileCountY>' >>"$e/tms.xml"
printf '<YOrigin>top</YOrigin></DataWindow><Projection>EPSG:3857</Projection><BlockSizeX>256</BlockSizeX><BlockSizeY>256</BlockSizeY></GDAL_WMS>\n' >>"$e/tms.xml"
# a raw band: a file's bytes as heights (the OBJ would spell root:x:0:0)
printf '<VRTDataset rasterXSize="64" rasterYSize="64"><SRS>EPSG:4326</SRS><GeoTransform>84,0.01,0,32,0,-0.01</GeoTransform>' >"$e/raw.vrt"
printf '<VRTRasterBand dataType="Byte" band="1" subClass="VRTRawRasterBand"><SourceFilename relativeToVRT="0">%s</SourceFilename>' "$tmp/elsewhere/secret.txt" >>"$e/raw.vrt"
printf '<ImageOffset>0</ImageOffset><PixelOffset>1</PixelOffset><LineOffset>64</LineOffset></VRTRasterBand></VRTDataset>\n' >>"$e/raw.vrt"
sed "s#$tmp/elsewhere/secret.txt#fifo.tif#; s#relativeToVRT=\"0\"#relativeToVRT=\"1\"#" "$e/raw.vrt" >"$e/rawfifo.vrt"
cp "$tmp/elsewhere/secret.txt" "$e/token.txt" # a raw band on a file beside the VRT: still bytes no one named
sed "s#$tmp/elsewhere/secret.txt#token.txt#; s#relativeToVRT=\"0\"#relativeToVRT=\"1\"#" "$e/raw.vrt" >"$e/rawmem.vrt"
vrt "rawmem.vrt" 1 >"$e/rawnested.vrt" # the raw band one VRT down
vrt "MEM:::DATAPOINTER=4096,PIXELS=64,LINES=64" 0 >"$e/memptr.vrt"
# the same through what a byte scan does not see: XML entities, an archive, a window on a file, inline XML
sed 's/VRTRawRasterBand/VRTRaw\&#82;asterBand/' "$e/rawmem.vrt" >"$e/rawentity.vrt"
vrt "MEM&#58;::DATAPOINTER=4096,PIXELS=64,LINES=64" 0 >"$e/mementity.vrt"
gzip -c "$e/rawmem.vrt" >"$e/raw.vrt.gz"
vrt "/vsigzip/$e/raw.vrt.gz" 0 >"$e/gzip.vrt"
vrt "/vsisubfile/0_$(wc -c <"$e/rawmem.vrt"),$e/rawmem.vrt" 0 >"$e/subfile.vrt"
vrt "$(sed 's/&/\&amp;/g; s/</\&lt;/g; s/>/\&gt;/g' "$e/rawmem.vrt" | tr -d '\n')" 0 >"$e/inline.vrt"
vrt "/vsicurl?url=$url/dem.tif" 0 >"$e/curlq.vrt"
vrt "/vsistdin?buffer_limit=1" 0 >"$e/stdinq.vrt"
# a link the user names, to a file elsewhere: that file opens, its folder does not
cp "$e/dem.tif" "$tmp/elsewhere/other.tif"
ln -s "$tmp/elsewhere/dem.tif" "$e/link.tif"
vrt "$tmp/elsewhere/other.tif" 0 >"$e/sibling.vrt"
# vectors: an OGR VRT on a WFS, on PostgreSQL, on a CSV outside the folder; a GML whose schema is a URL
ogrvrt() { printf '<OGRVRTDataSource><OGRVRTLayer name="x"><SrcDataSource>%s</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>\n' "$1"; }
ogrvrt "WFS:$url/wfs" >"$e/wfs.vrt"
ogrvrt "PG:host=127.0.0.1 port=$port dbname=x user=x" >"$e/pg.vrt"
ogrvrt "$tmp/elsewhere/secret.txt" >"$e/csv.vrt"
ogrvrt "/proc/self/environ" >"$e/proccsv.vrt"
printf '<?xml version="1.0"?><x:FeatureCollection xmlns:x="http://x" xmlns:gml="http://www.opengis.net/gml" xsi:schemaLocation="http://x %s/schema.xsd" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"><gml:featureMember><x:p><x:g><gml:Point><gml:coordinates>86.9,28</gml:coordinates></gml:Point></x:g></x:p></gml:featureMember></x:FeatureCollection>\n' "$url" >"$e/schema.gml"
printf '{"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"$ref":"%s/g.json"}}]}\n' "$url" >"$e/ref.geojson"

count() { cat "$tmp/count"; }
# attack NAME FILE [may-open]: every entry point opens FILE; none may connect, hang, or take bytes it was
# not given; a file that is data in its own right (may-open) may be drawn without what it points to
attack() {
    name=$1 f=$2 may=$3
    before=$(count)
    o=$tmp/out
    for how in dem imagery vectors viewshed track mesh water flood; do
        rm -rf "$o"/* "$o"/.[!.]*
        case $how in
            dem) set -- --dem "$f" --output "$o/x.png" --size 16x9 --spp 1 --quiet ;;
            imagery) set -- --dem "$e/dem.tif" --set "terrain.imagery=$f" --output "$o/x.png" --size 16x9 --spp 1 --quiet ;;
            vectors) set -- --dem "$e/dem.tif" --set "terrain.vectors=$f" --output "$o/x.png" --size 16x9 --spp 1 --quiet ;;
            viewshed) set -- viewshed --dem "$f" --observer 86.9,28 --output "$o/x.tif" ;;
            track) set -- track --dem "$e/dem.tif" --input "$f" --output "$o/x.json" ;;
            mesh) set -- mesh --dem "$f" --resolution 16 --output "$o/x.obj" --quiet ;;
            water) set -- water --dem "$f" --output "$o/x.tif" ;;
            flood) set -- --dem "$e/dem.tif" --set "terrain.water=$f" --output "$o/x.png" --size 16x9 --spp 1 --quiet ;;
        esac
        timeout 60 "$fathom" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
        code=$?
        why=""
        [ $code -eq 124 ] && why="hung (killed after 60 s)"
        [ $code -gt 124 ] && why="crashed (exit $code)"
        [ $code -eq 0 ] && [ -z "$may" ] && why="accepted"
        grep -rq 'root:x\|FAKESECRET\|root\\:x' "$o" "$tmp/stderr" 2>/dev/null && why="$why; the secret reached the output"
        if [ -z "$why" ]; then ok "$name via $how: exit $code ($(tail -n 1 "$tmp/stderr" | head -c 150))"; else bad "$name via $how: $why"; fi
    done
    sleep 0.5 # the listener polls every 0.2 s: a connection the last run made is counted by now
    kill -0 "$lpid" 2>/dev/null || { failed=$((failed + 1)); echo "FAIL the listener is gone: nothing would be counted"; }
    after=$(count)
    if [ "$before" = "$after" ]; then ok "$name: no connection"; else
        failed=$((failed + 1)); echo "FAIL $name: $((after - before)) connection(s) to the listener"; fi
}

for f in http.vrt vsicurl.vrt wmsconn.vrt wms.xml wcs.xml tms.xml outside.vrt updir.vrt stdin.vrt vsistdin.vrt \
    fifo.vrt proc.vrt raw.vrt rawfifo.vrt rawmem.vrt rawnested.vrt memptr.vrt rawentity.vrt mementity.vrt gzip.vrt \
    subfile.vrt inline.vrt curlq.vrt stdinq.vrt wfs.vrt pg.vrt csv.vrt proccsv.vrt; do
    attack "$f" "$e/$f"
done
attack schema.gml "$e/schema.gml" may-open
attack ref.geojson "$e/ref.geojson" may-open
# a path that is itself a service, a device or GDAL's virtual file system
for f in "$url/dem.tif" "/vsicurl/$url/dem.tif" "WMS:$url/wms" "PG:host=127.0.0.1 port=$port" /dev/stdin /vsistdin/ \
    "$e/fifo.tif" /proc/self/environ; do
    attack "named $f" "$f"
done

run timeout 60 "$fathom" --dem "$e/link.tif" --output "$tmp/out/link.png" --size 16x9 --spp 1 --quiet
check "a named link to a file elsewhere: drawn" '[ $code -eq 0 ] && [ -s "$tmp/out/link.png" ]'
run timeout 60 "$fathom" --dem "$e/link.tif" --set "terrain.imagery=$e/sibling.vrt" --output "$tmp/out/sib.png" \
    --size 16x9 --spp 1 --quiet
check "... its target's folder not opened by it" '[ $code -ne 0 ] && [ ! -e "$tmp/out/sib.png" ]'

# the control: the folder's own files still open, and a VRT mosaic of them too
timeout 120 "$fathom" --dem "$e/inside.vrt" --output "$tmp/out/ok.png" --size 16x9 --spp 1 --quiet 2>"$tmp/stderr" &&
    [ -s "$tmp/out/ok.png" ] && ok "a VRT of its own folder's DEM: drawn" || bad "a VRT of its own folder's DEM: not drawn"
timeout 120 "$fathom" viewshed --dem "$e/inside.vrt" --observer 86.9,28 --output "$tmp/out/ok.tif" 2>"$tmp/stderr" &&
    [ -s "$tmp/out/ok.tif" ] && ok "a VRT of its own folder's DEM: its viewshed" || bad "a VRT of its own folder's DEM: no viewshed"
timeout 120 "$fathom" viewshed --dem "NETCDF:\"$e/dem.tif\":z" --observer 86.9,28 --output "$tmp/out/nc.tif" 2>"$tmp/stderr"
grep -q "cannot read DEM" "$tmp/stderr" && ! grep -q "local files only" "$tmp/stderr" && ok "NETCDF:\"FILE\":VAR reaches GDAL (the file checked)" ||
    bad "NETCDF:\"FILE\":VAR: not read as a netCDF variable"

finish trust_gis
