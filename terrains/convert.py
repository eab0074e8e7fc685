#!/usr/bin/env python3
"""Makes the heightmaps in terrains/ from Debian packages (standard library + oiiotool only).

    python3 terrains/convert.py        # from the repository root; needs apt-get and oiiotool

Each terrain becomes NAME.png (16-bit grey: 0..65535 maps to height_min..height_max metres) and
NAME.json (spacing in metres per texel along x and z, the height range, origin and licence).
Rows run north to south (the image's top row is the northern edge, world −Z); columns west to east (+X).
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
    path = fetch("ferret-datasets", "/usr/share/ferret-vis/data/etopo5.cdf")
    W, H, OFFSET = 4320, 2161, 52552  # float32 big-endian grid, rows south→north, lon 0→360 (design.md)
    lat0, lat1, lon0, lon1 = 26.0, 38.0, 76.0, 96.0  # the Himalaya and the southern Tibetan plateau
    step = 1.0 / 12.0  # 5 arc minutes
    i0, i1 = round(lon0 / step), round(lon1 / step)
    j0, j1 = round((lat0 + 90) / step), round((lat1 + 90) / step)
    rows = []
    with open(path, "rb") as f:
        for j in range(j1, j0 - 1, -1):  # north first
            f.seek(OFFSET + 4 * (j * W + i0))
            rows.append(list(struct.unpack(">%df" % (i1 - i0 + 1), f.read(4 * (i1 - i0 + 1)))))
    metres_per_degree = 6371000.0 * math.pi / 180.0
    lat_mid = math.radians(0.5 * (lat0 + lat1))
    write("himalaya", rows, [step * metres_per_degree * math.cos(lat_mid), step * metres_per_degree],
          "ETOPO5 world relief (NOAA NGDC, 5 arc minutes), 26-38 N, 76-96 E; package ferret-datasets, "
          "usr/share/ferret-vis/data/etopo5.cdf",
          "public domain (US government data, NOAA NGDC)",
          "python3 terrains/convert.py")


if __name__ == "__main__":
    jacksboro()
    himalaya()
