#!/usr/bin/env python3
"""Makes the heightmaps in terrains/ from Debian packages (standard library, oiiotool, gdal-bin).

    python3 terrains/convert.py        # from the repository root; needs apt-get, oiiotool, gdal_translate

jacksboro becomes jacksboro.png (16-bit grey: 0..65535 maps to height_min..height_max metres) and
jacksboro.json (spacing in metres per texel along x and z, the height range, origin and licence): an
image with a sidecar, as a user without GIS tools would make one. himalaya becomes himalaya.tif, a
georeferenced Int16 GeoTIFF in metres (EPSG:4326) that GDAL cuts from ETOPO5's netCDF: a real DEM as a
GIS user has one. Rows run north to south (the top row is the northern edge, world −Z); columns west
to east (+X).
"""
import glob, json, math, os, struct, subprocess, sys, tempfile, zipfile

HERE = os.path.dirname(os.path.abspath(__file__))


def fetch(package, member):
    tmp = tempfile.mkdtemp()
    subprocess.run(["apt-get", "download", package], cwd=tmp, check=True, stdout=subprocess.DEVNULL)
    deb = glob.glob(os.path.join(tmp, package + "_*.deb"))[0]
    tar = subprocess.run(["dpkg-deb", "--fsys-tarfile", deb], check=True, stdout=subprocess.PIPE).stdout
    out = subprocess.run(["tar", "-x", "-C", tmp, "." + member], input=tar, check=True)
    return os.path.join(tmp, member.lstrip("/"))


def npy(data):
    """A little-endian .npy array: (dtype, shape, raw bytes)."""
    hl = struct.unpack("<H", data[8:10])[0]
    header = eval(data[10:10 + hl].decode())  # a Python dict literal, as .npy defines it
    return header["descr"], header["shape"], data[10 + hl:]


def write(name, rows, spacing, origin, licence, command):
    """rows: list of lists of metres, north row first."""
    lo = min(min(r) for r in rows)
    hi = max(max(r) for r in rows)
    h, w = len(rows), len(rows[0])
    pgm = os.path.join(tempfile.mkdtemp(), name + ".pgm")
    with open(pgm, "wb") as f:
        f.write(b"P5\n%d %d\n65535\n" % (w, h))
        for r in rows:
            f.write(b"".join(struct.pack(">H", round((v - lo) / (hi - lo) * 65535)) for v in r))
    subprocess.run(["oiiotool", pgm, "-d", "uint16", "-o", os.path.join(HERE, name + ".png")], check=True)
    meta = {"spacing": spacing, "height_min": lo, "height_max": hi, "width": w, "height": h,
            "origin": origin, "licence": licence, "made_by": command}
    with open(os.path.join(HERE, name + ".json"), "w") as f:
        json.dump(meta, f, indent=2)
        f.write("\n")
    print("%s: %dx%d texels, %.1f x %.1f m each, heights %.1f .. %.1f m" % (name, w, h, spacing[0], spacing[1], lo, hi))


def jacksboro():
    path = fetch("python-matplotlib-data", "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz")
    z = zipfile.ZipFile(path)
    descr, shape, raw = npy(z.read("elevation.npy"))
    assert descr == "<i2"
    vals = struct.unpack("<%dh" % (shape[0] * shape[1]), raw)
    rows = [list(vals[i * shape[1]:(i + 1) * shape[1]]) for i in range(shape[0])]
    scalar = lambda key: struct.unpack("<d", npy(z.read(key + ".npy"))[2])[0]
    # spacing is in degrees (3 arc seconds): metres at the DEM's mean latitude
    metres_per_degree = 6371000.0 * math.pi / 180.0
    lat_mid = math.radians(0.5 * (scalar("ymin") + scalar("ymax")))
    dx = scalar("dx") * metres_per_degree * math.cos(lat_mid)
    dz = scalar("dy") * metres_per_degree
    # matplotlib's hillshade example shows row 0 as the north edge (imshow, origin upper)
    write("jacksboro", rows, [dx, dz],
          "Jacksboro fault, Tennessee: matplotlib sample data (USGS 90 m DEM), package python-matplotlib-data, "
          "usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz",
          "matplotlib licence (BSD-style, PSF-based); the DEM is USGS data (public domain)",
          "python3 terrains/convert.py")


def himalaya():
    """ETOPO5's netCDF, cut to 26-38 N, 76-96 E by GDAL into a georeferenced Int16 GeoTIFF: fathom reads
    it through GDAL, which gives the spacing (5 arc minutes at the central latitude) and the heights."""
    path = fetch("ferret-datasets", "/usr/share/ferret-vis/data/etopo5.cdf")
    # grid: 4320 x 2161, rows north to south from 90 N, columns from 0 E, 12 per degree
    lon0, lat1, cols, rows = 76, 38, 241, 145  # 76-96 E, 38-26 N, every 5 arc minutes
    out = os.path.join(HERE, "himalaya.tif")
    subprocess.run(["gdal_translate", "-q", "-of", "GTiff", "-ot", "Int16", "-a_nodata", "-32768", "-a_srs", "EPSG:4326",
                    "-srcwin", str(lon0 * 12), str((90 - lat1) * 12), str(cols), str(rows),
                    "-co", "COMPRESS=DEFLATE", "-co", "PREDICTOR=2",
                    "-mo", "ORIGIN=ETOPO5 world relief (NOAA NGDC, 5 arc minutes); package ferret-datasets, "
                    "usr/share/ferret-vis/data/etopo5.cdf",
                    "-mo", "LICENCE=public domain (US government data, NOAA NGDC)",
                    "-mo", "MADE_BY=python3 terrains/convert.py",
                    "NETCDF:" + path + ":ROSE", out], check=True)
    print("himalaya: " + subprocess.run(["gdalinfo", "-stats", out], check=True, stdout=subprocess.PIPE,
                                        text=True).stdout.split("Size is ")[1].split("\n")[0] + " texels")
    for junk in glob.glob(out + ".aux.xml"):
        os.remove(junk)


def bluemarble():
    """NASA's Blue Marble (2048 x 1024, plate carree, whole Earth) cut to the Himalaya DEM's area as a
    georeferenced RGB GeoTIFF: imagery to drape on himalaya.tif (docs/guide/gis.md)."""
    path = fetch("xplanet-images", "/usr/share/xplanet/images/earth.jpg")
    deg = 360 / 2048  # a pixel; rows from 90 N, columns from 180 W
    x0, y0, cols, rows = 1456, 295, 115, 70  # 75.94-96.15 E, 38.14-25.84 N: covers the DEM
    out = os.path.join(HERE, "himalaya-bluemarble.tif")
    subprocess.run(["gdal_translate", "-q", "-a_srs", "EPSG:4326", "-a_ullr", str(x0 * deg - 180), str(90 - y0 * deg),
                    str((x0 + cols) * deg - 180), str(90 - (y0 + rows) * deg), "-srcwin", str(x0), str(y0), str(cols),
                    str(rows), "-co", "COMPRESS=DEFLATE",
                    "-mo", "SOURCE=NASA Visible Earth Blue Marble (xplanet-images 1.3.1-3: usr/share/xplanet/images/"
                    "earth.jpg, 2048x1024 plate carree)",
                    "-mo", "LICENCE=NASA imagery, not copyrighted (the package's images/README)",
                    path, out], check=True)
    print("himalaya-bluemarble: %dx%d pixels of %.4f degrees" % (cols, rows, deg))


if __name__ == "__main__":
    jacksboro()
    himalaya()
    bluemarble()
