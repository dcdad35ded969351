#!/usr/bin/python3
"""Drone-like photos from renders: each view_NNN.png of a kept-views folder as a JPEG whose EXIF holds the GPS
fix a drone would have written (bench/README.md, "reconstruct"). The render camera's centre (metres, x east,
y north, z up: cameras.json) is placed at --origin on the WGS84 ellipsoid and given receiver noise (Gaussian,
--noise-m horizontal, --vertical-noise-m vertical, per photo, seeded), so the GPS path of lc2wf-reconstruct
can be scored against the known cameras.

usage: geotag_views.py VIEWS_DIR OUT_DIR [--origin LAT,LON,ALT] [--noise-m S] [--vertical-noise-m S] [--seed N]
"""
import argparse
import json
import math
import pathlib
import random
import sys

from PIL import Image
from PIL.TiffImagePlugin import IFDRational

WGS84_A = 6378137.0
WGS84_E2 = 6.69437999014e-3
GPS_IFD = 0x8825


def ecef(lat_deg, lon_deg, h):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = WGS84_A / math.sqrt(1 - WGS84_E2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1 - WGS84_E2) + h) * math.sin(lat))


def geodetic(x, y, z):
    """ECEF -> latitude, longitude (degrees), height (m); fixed-point iteration, converged to < 1 mm here."""
    lon = math.atan2(y, x)
    p = math.hypot(x, y)
    lat = math.atan2(z, p * (1 - WGS84_E2))
    h = 0.0
    for _ in range(10):
        n = WGS84_A / math.sqrt(1 - WGS84_E2 * math.sin(lat) ** 2)
        h = p / math.cos(lat) - n
        lat = math.atan2(z, p * (1 - WGS84_E2 * n / (n + h)))
    return math.degrees(lat), math.degrees(lon), h


def enu_to_geodetic(origin, east, north, up):
    lat0, lon0, h0 = origin
    phi, lam = math.radians(lat0), math.radians(lon0)
    ox, oy, oz = ecef(lat0, lon0, h0)
    # Columns of the ENU -> ECEF rotation: east, north, up at the origin.
    dx = -math.sin(lam) * east - math.sin(phi) * math.cos(lam) * north + math.cos(phi) * math.cos(lam) * up
    dy = math.cos(lam) * east - math.sin(phi) * math.sin(lam) * north + math.cos(phi) * math.sin(lam) * up
    dz = math.cos(phi) * north + math.sin(phi) * up
    return geodetic(ox + dx, oy + dy, oz + dz)


def dms(value_deg):
    """Degrees, minutes, seconds as EXIF rationals (seconds to 1e-4 s: about 3 mm)."""
    v = abs(value_deg)
    d = int(v)
    m = int((v - d) * 60)
    s = round(((v - d) * 60 - m) * 60 * 10000)
    return (IFDRational(d, 1), IFDRational(m, 1), IFDRational(s, 10000))


def camera_centre(cam):
    r, t = cam["R"], cam["t"]
    return [-(r[0 + i] * t[0] + r[3 + i] * t[1] + r[6 + i] * t[2]) for i in range(3)]


def gps_exif(lat, lon, alt):
    exif = Image.Exif()
    exif[GPS_IFD] = {
        0: b"\x02\x03\x00\x00",  # GPSVersionID
        1: "N" if lat >= 0 else "S", 2: dms(lat),
        3: "E" if lon >= 0 else "W", 4: dms(lon),
        5: b"\x00" if alt >= 0 else b"\x01", 6: IFDRational(round(abs(alt) * 1000), 1000),
    }
    return exif.tobytes()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("views", type=pathlib.Path, help="a kept-views folder (view_NNN.png, cameras.json)")
    ap.add_argument("out", type=pathlib.Path, help="folder for view_NNN.jpg (created)")
    ap.add_argument("--origin", default="52.0116,4.3571,0", help="LAT,LON,ALT of the cameras' frame origin")
    ap.add_argument("--noise-m", type=float, default=1.5, help="horizontal receiver noise, metres (1 sigma per axis)")
    ap.add_argument("--vertical-noise-m", type=float, default=0.5, help="vertical receiver noise, metres (1 sigma)")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    try:
        origin = tuple(float(v) for v in a.origin.split(","))
        if len(origin) != 3 or not (-90 < origin[0] < 90 and -180 <= origin[1] <= 180):
            raise ValueError
    except ValueError:
        sys.exit(f"geotag_views.py: --origin must be LAT,LON,ALT (got {a.origin!r})")
    if a.noise_m < 0 or a.vertical_noise_m < 0:
        sys.exit("geotag_views.py: --noise-m and --vertical-noise-m must be >= 0")
    cams = json.loads((a.views / "cameras.json").read_text())
    images = sorted(a.views.glob("view_*.png"))
    if len(images) != len(cams):
        sys.exit(f"geotag_views.py: {a.views}: {len(images)} views but {len(cams)} cameras")
    rng = random.Random(a.seed)
    a.out.mkdir(parents=True, exist_ok=True)
    for image, cam in zip(images, cams):
        e, n, u = camera_centre(cam)
        e += rng.gauss(0, a.noise_m)
        n += rng.gauss(0, a.noise_m)
        u += rng.gauss(0, a.vertical_noise_m)
        lat, lon, alt = enu_to_geodetic(origin, e, n, u)
        target = a.out / (image.stem + ".jpg")
        scratch = target.with_suffix(".jpg.part")
        Image.open(image).convert("RGB").save(scratch, "JPEG", quality=95, exif=gps_exif(lat, lon, alt))
        scratch.replace(target)


if __name__ == "__main__":
    main()
