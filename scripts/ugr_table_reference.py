#!/usr/bin/env python3
"""An independent CIE 190 UGR table of a EULUMDAT file, for core/glare's test.

    python3 scripts/ugr_table_reference.py FILE.ldt > table.csv

Writes 19 rows (CIE 190's rooms, 2Hx2H ... 12Hx8H) by 10 columns (crosswise, then endwise;
reflectances 70/50/20, 70/30/20, 50/50/20, 50/30/20, 30/30/20), two decimals, no header.

It shares no code with ilp (core/glare/ugr_table.cpp) and takes another route where it can:
- its own EULUMDAT reader (fields 1-30, every Isym), intensity by plain bilinear
  interpolation on the file's own web (ilp: monotone cubic, then a fine bilinear table);
- each luminaire's angles from R, T, H as in CIE 117 eq. 4.5-4.8 (gamma = atan(sqrt(R^2 + T^2) / H);
  C = atan(T/R) crosswise, 90 - atan(T/R) endwise, with the sign of T kept so that a web that is
  not symmetric about the line of sight is read on the side each luminaire shows), not from
  rotating frames;
- the luminance as I / projected area with the sides of the luminous area seen at (C, gamma);
- the position index by its own bilinear lookup in CIE 117 Table 4.1;
- the background luminance by CIE 190's flux transfer (zonal flux at the 10-degree zone
  middles from the file's own C planes, geometric factors F_GL by room index, transfer
  factors F_T), Lb = E_WID / pi.
The two CIE tables (4.1 of CIE 117; 4 and 5 of CIE 190) are data and are the same numbers as in
ilp (transcribed in eulumdat-ugr, MIT, github.com/123VincentB/eulumdat-ugr); the opening
convention is ilp's (EULUMDAT luminous length along C0-C180). Standard library only.
"""
import math
import sys

ROOMS = [(2, 2), (2, 3), (2, 4), (2, 6), (2, 8), (2, 12), (4, 2), (4, 3), (4, 4), (4, 6), (4, 8), (4, 12),
         (8, 4), (8, 6), (8, 8), (8, 12), (12, 4), (12, 6), (12, 8)]

GUTH = """1.00 1.26 1.53 1.90 2.35 2.86 3.50 4.20 5.00 6.00 7.00 8.10 9.25 10.35 11.70 13.15 14.70 16.20 - -
1.05 1.22 1.46 1.80 2.20 2.75 3.40 4.10 4.80 5.80 6.80 8.00 9.10 10.30 11.60 13.00 14.60 16.10 - -
1.12 1.30 1.50 1.80 2.20 2.66 3.18 3.88 4.60 5.50 6.50 7.60 8.75 9.85 11.20 12.70 14.00 15.70 - -
1.22 1.38 1.60 1.97 2.25 2.70 3.25 3.90 4.60 5.45 6.45 7.40 8.40 9.50 10.85 12.10 13.70 15.00 - -
1.32 1.47 1.70 1.96 2.35 2.80 3.30 3.90 4.60 5.40 6.40 7.30 8.30 9.40 10.60 11.90 13.20 14.60 16.00 -
1.43 1.60 1.82 2.10 2.48 2.91 3.40 3.98 4.70 5.50 6.40 7.30 8.30 9.40 10.50 11.75 13.00 14.40 15.70 -
1.55 1.72 1.98 2.30 2.65 3.10 3.60 4.10 4.80 5.50 6.40 7.35 8.40 9.40 10.50 11.70 13.00 14.10 15.40 -
1.70 1.88 2.12 2.48 2.87 3.30 3.78 4.30 4.88 5.60 6.50 7.40 8.50 9.50 10.50 11.70 12.85 14.00 15.20 -
1.82 2.00 2.32 2.70 3.08 3.50 3.92 4.50 5.10 5.75 6.60 7.50 8.60 9.50 10.60 11.75 12.80 14.00 15.10 -
1.96 2.20 2.54 2.90 3.30 3.70 4.20 4.75 5.30 6.00 6.75 7.70 8.70 9.65 10.75 11.80 12.90 14.00 15.00 16.00
2.11 2.40 2.75 3.10 3.50 3.91 4.40 5.00 5.60 6.20 7.00 7.90 8.80 9.75 10.80 11.90 12.95 14.00 15.00 16.00
2.30 2.55 2.92 3.30 3.72 4.20 4.70 5.25 5.80 6.55 7.20 8.15 9.00 9.90 10.95 12.00 13.00 14.00 15.00 16.00
2.40 2.75 3.12 3.50 3.90 4.35 4.85 5.50 6.05 6.70 7.50 8.30 9.20 10.00 11.02 12.10 13.10 14.00 15.00 16.00
2.55 2.90 3.30 3.70 4.20 4.65 5.20 5.70 6.30 7.00 7.70 8.55 9.35 10.20 11.20 12.25 13.20 14.00 15.00 16.00
2.70 3.10 3.50 3.90 4.35 4.85 5.35 5.85 6.50 7.25 8.00 8.70 9.50 10.40 11.40 12.40 13.25 14.05 15.00 16.00
2.85 3.15 3.65 4.10 4.55 5.00 5.50 6.20 6.80 7.50 8.20 8.85 9.70 10.55 11.50 12.50 13.30 14.05 15.02 16.00
2.95 3.40 3.80 4.25 4.75 5.20 5.75 6.30 7.00 7.65 8.40 9.00 9.80 10.80 11.75 12.60 13.40 14.20 15.10 16.00
3.10 3.55 4.00 4.50 4.90 5.40 5.95 6.50 7.20 7.80 8.50 9.20 10.00 10.85 11.85 12.75 13.45 14.20 15.10 16.00
3.25 3.70 4.20 4.65 5.10 5.60 6.10 6.75 7.40 8.00 8.65 9.35 10.10 11.00 11.90 12.80 13.50 14.20 15.10 16.00
3.43 3.86 4.30 4.75 5.20 5.70 6.30 6.90 7.50 8.17 8.80 9.50 10.20 11.00 12.00 12.82 13.55 14.20 15.10 16.00
3.50 4.00 4.50 4.90 5.35 5.80 6.40 7.10 7.70 8.30 8.90 9.60 10.40 11.10 12.00 12.85 13.60 14.30 15.10 16.00
3.60 4.17 4.65 5.05 5.50 6.00 6.60 7.20 7.82 8.45 9.00 9.75 10.50 11.20 12.10 12.90 13.70 14.35 15.10 16.00
3.75 4.25 4.72 5.20 5.60 6.10 6.70 7.35 8.00 8.55 9.15 9.85 10.60 11.30 12.10 12.90 13.70 14.40 15.15 16.00
3.85 4.35 4.80 5.25 5.70 6.22 6.80 7.40 8.10 8.65 9.30 9.90 10.70 11.40 12.20 12.95 13.70 14.40 15.20 16.00
3.95 4.40 4.90 5.35 5.80 6.30 6.90 7.50 8.20 8.80 9.40 10.00 10.80 11.50 12.25 13.00 13.75 14.45 15.20 16.00
4.00 4.50 4.96 5.40 5.85 6.40 6.95 7.55 8.25 8.85 9.50 10.05 10.85 11.55 12.30 13.00 13.80 14.50 15.25 16.00
4.07 4.55 5.05 5.47 5.95 6.46 7.00 7.65 8.35 8.95 9.55 10.10 10.90 11.60 12.32 13.00 13.80 14.50 15.25 16.00
4.10 4.60 5.10 5.53 6.00 6.50 7.50 7.70 8.40 9.00 9.60 10.16 10.92 11.63 12.35 13.00 13.80 14.50 15.25 16.00
4.15 4.62 5.15 5.56 6.05 6.55 7.08 7.73 8.45 9.05 9.65 10.20 10.95 11.65 12.35 13.00 13.80 14.50 15.25 16.00
4.20 4.65 5.17 5.60 6.07 6.57 7.12 7.75 8.50 9.10 9.70 10.23 10.95 11.65 12.35 13.00 13.80 14.50 15.25 16.00
4.22 4.67 5.20 5.65 6.12 6.60 7.15 7.80 8.55 9.12 9.70 10.23 10.95 11.65 12.35 13.00 13.80 14.50 15.25 16.00"""
GUTH_ROWS = [[None if v == "-" else float(v) for v in line.split()] for line in GUTH.splitlines()]

# CIE 190 Table 4 (F_GL1..4 by k) and Table 5 (F_T FW, WW-1, CW per room, per reflectance set).
FGL = {1.00: (0.690, 0.109, 0.085, -0.016), 1.20: (0.578, 0.200, 0.127, -0.018), 1.33: (0.528, 0.218, 0.170, -0.017),
       1.50: (0.485, 0.215, 0.222, -0.012), 1.60: (0.466, 0.207, 0.249, -0.006), 1.71: (0.448, 0.198, 0.272, 0.005),
       2.00: (0.338, 0.257, 0.351, -0.018), 2.40: (0.296, 0.203, 0.449, -0.006), 2.67: (0.280, 0.165, 0.499, 0.006),
       3.00: (0.264, 0.125, 0.541, 0.027), 3.43: (0.248, 0.058, 0.628, 0.032), 4.00: (0.239, -0.012, 0.690, 0.058),
       4.80: (0.232, -0.084, 0.740, 0.098)}
FT = [
    "0.220 0.422 0.646 0.199 0.376 0.571 0.187 0.351 0.531 0.174 0.322 0.488 0.167 0.307 0.466 0.160 0.290 0.443 "
    "0.187 0.351 0.531 0.158 0.295 0.439 0.142 0.265 0.389 0.124 0.230 0.335 0.115 0.211 0.307 0.105 0.190 0.279 "
    "0.115 0.211 0.307 0.094 0.175 0.247 0.083 0.155 0.215 0.071 0.133 0.183 0.105 0.190 0.279 0.083 0.153 0.216 "
    "0.071 0.133 0.183",
    "0.188 0.217 0.553 0.173 0.196 0.497 0.164 0.184 0.465 0.154 0.171 0.432 0.149 0.164 0.415 0.143 0.156 0.397 "
    "0.164 0.184 0.465 0.142 0.159 0.393 0.129 0.144 0.351 0.114 0.127 0.307 0.106 0.117 0.283 0.098 0.106 0.259 "
    "0.106 0.117 0.283 0.088 0.098 0.231 0.078 0.088 0.203 0.067 0.076 0.174 0.098 0.106 0.259 0.078 0.086 0.204 "
    "0.067 0.076 0.174",
    "0.198 0.380 0.445 0.178 0.338 0.393 0.166 0.314 0.365 0.154 0.287 0.335 0.147 0.273 0.320 0.141 0.257 0.304 "
    "0.166 0.314 0.364 0.140 0.263 0.301 0.125 0.235 0.267 0.108 0.204 0.230 0.100 0.187 0.211 0.091 0.167 0.191 "
    "0.100 0.187 0.211 0.081 0.154 0.169 0.071 0.137 0.147 0.061 0.117 0.125 0.091 0.167 0.191 0.071 0.134 0.148 "
    "0.061 0.117 0.125",
    "0.172 0.198 0.386 0.157 0.179 0.346 0.148 0.167 0.324 0.138 0.155 0.301 0.133 0.147 0.288 0.128 0.140 0.276 "
    "0.148 0.167 0.324 0.126 0.143 0.272 0.114 0.129 0.244 0.100 0.113 0.212 0.093 0.104 0.196 0.085 0.094 0.179 "
    "0.093 0.104 0.196 0.076 0.087 0.158 0.067 0.078 0.140 0.058 0.067 0.120 0.085 0.094 0.179 0.068 0.077 0.140 "
    "0.058 0.067 0.120",
    "0.157 0.181 0.227 0.141 0.162 0.203 0.132 0.151 0.190 0.123 0.139 0.176 0.118 0.132 0.169 0.113 0.124 0.161 "
    "0.132 0.151 0.190 0.112 0.128 0.159 0.100 0.115 0.142 0.087 0.101 0.124 0.081 0.092 0.114 0.074 0.083 0.104 "
    "0.081 0.092 0.114 0.066 0.077 0.092 0.058 0.069 0.081 0.049 0.059 0.069 0.074 0.083 0.104 0.058 0.067 0.081 "
    "0.049 0.059 0.069",
]
FT = [[tuple(map(float, s.split()[3 * i:3 * i + 3])) for i in range(19)] for s in FT]


def read_ldt(path):
    lines = open(path, encoding="latin-1").read().lstrip("\ufeff\u00ef\u00bb\u00bf").splitlines()
    f = [x.strip() for x in lines]
    isym, mc, ng = int(f[2]), int(f[3]), int(f[5])
    n_sets = int(f[25])
    counts = [float(f[26 + 6 * s]) for s in range(n_sets)]
    flux = [float(f[28 + 6 * s]) for s in range(n_sets)]
    at = 26 + 6 * n_sets + 10  # after the lamp sets and the 10 direct ratios
    c_angles = [float(x) for x in f[at:at + mc]]
    g_angles = [float(x) for x in f[at + mc:at + mc + ng]]
    mc1, mc2 = {0: (1, mc), 1: (1, 1), 2: (1, mc // 2 + 1), 3: (3 * mc // 4 + 1, 3 * mc // 4 + 1 + mc // 2),
                4: (1, mc // 4 + 1)}[isym]
    values = [float(x) for x in f[at + mc + ng:at + mc + ng + (mc2 - mc1 + 1) * ng]]
    lamp_lm = abs(counts[0]) * flux[0] if counts[0] > 0 else flux[0]
    scale = lamp_lm / 1000.0 * float(f[23])
    stored = {c_angles[mc1 - 1 + i]: [v * scale for v in values[i * ng:(i + 1) * ng]] for i in range(mc2 - mc1 + 1)}
    planes = {}  # the full circle of C planes from the symmetry
    for c in c_angles:
        if isym == 1:
            src = c_angles[0]
        elif isym == 2:
            src = c if c <= 180 else 360 - c
        elif isym == 3:
            src = c if 90 <= c <= 270 else (180 - c) % 360
        elif isym == 4:
            cc = c % 180
            src = cc if cc <= 90 else 180 - cc
        else:
            src = c
        planes[c] = stored[min(stored, key=lambda s: abs(s - src))]
    dims = [float(x) / 1000.0 for x in f[12:21]]
    return dict(c=sorted(planes), g=g_angles, planes=planes, dims=dims)


def interp(xs, ys, x):
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1] if x == xs[-1] else 0.0
    for i in range(len(xs) - 1):
        if xs[i] <= x <= xs[i + 1]:
            u = (x - xs[i]) / (xs[i + 1] - xs[i])
            return ys[i] * (1 - u) + ys[i + 1] * u


def intensity(ldt, c, g):
    cs = ldt["c"] + [360.0]
    rows = [ldt["planes"][x] for x in ldt["c"]] + [ldt["planes"][ldt["c"][0]]]
    c %= 360.0
    if len(ldt["c"]) == 1:
        return interp(ldt["g"], rows[0], g)
    for i in range(len(cs) - 1):
        if cs[i] <= c <= cs[i + 1]:
            u = (c - cs[i]) / (cs[i + 1] - cs[i])
            return (1 - u) * interp(ldt["g"], rows[i], g) + u * interp(ldt["g"], rows[i + 1], g)


def flux_lm(ldt):  # trapezoid rule in gamma, then in C over the circle
    cs = ldt["c"] + [360.0]
    g = [math.radians(x) for x in ldt["g"]]
    per_plane = []
    for c in cs:
        row = ldt["planes"][c % 360.0 if c < 360 else ldt["c"][0]]
        per_plane.append(sum(0.5 * (row[i] * math.sin(g[i]) + row[i + 1] * math.sin(g[i + 1])) * (g[i + 1] - g[i])
                             for i in range(len(g) - 1)))
    if len(ldt["c"]) == 1:
        return per_plane[0] * 2 * math.pi
    return sum(0.5 * (per_plane[i] + per_plane[i + 1]) * math.radians(cs[i + 1] - cs[i]) for i in range(len(cs) - 1))


def projected_area(dims, c_deg, g_deg):
    length, width = dims[3], dims[4]
    height = max(dims[5:9])
    if length == 0 and width == 0:
        length, width, height = dims[0], dims[1], 0.0
    c, g = math.radians(c_deg), math.radians(g_deg)
    if width == 0:  # round
        return math.pi * length ** 2 / 4 * math.cos(g) + length * height * math.sin(g)
    return length * width * math.cos(g) + height * math.sin(g) * (width * abs(math.cos(c)) + length * abs(math.sin(c)))


def guth(h_r, t_r):
    t, h = abs(t_r) * 10, h_r * 10
    if t > 30 + 1e-9 or h < 0 or h > 19 + 1e-9:
        return None
    ti, hi = min(int(t), 29), min(int(h), 18)
    u, v = t - ti, h - hi
    cells = [GUTH_ROWS[ti][hi], GUTH_ROWS[ti][hi + 1], GUTH_ROWS[ti + 1][hi], GUTH_ROWS[ti + 1][hi + 1]]
    if None in cells:
        return None
    return (1 - u) * ((1 - v) * cells[0] + v * cells[1]) + u * ((1 - v) * cells[2] + v * cells[3])


def glare_sum(ldt, phi, x_h, y_h, endwise, H=2.0, shr=0.25):
    s = shr * H
    nx, ny = round(x_h / shr), round(y_h / shr)
    total = 0.0
    for j in range(ny):
        R = (j + 0.5) * s
        for i in range(nx):
            x = (i + 0.5 - nx / 2) * s  # across the line of sight
            T = abs(x)
            gamma = math.degrees(math.atan(math.hypot(R, T) / H))
            p = guth(H / R, T / R)
            if p is None or gamma > 85.0:
                continue
            # C of the direction to the eye. Crosswise the luminaire's C0 axis points at the
            # observer (room -y) and C90 to room +x; endwise C90 points at the observer and C0 to
            # room -x. The eye is at (-x, -R) from the luminaire.
            c = math.degrees(math.atan2(R, x) if endwise else math.atan2(-x, R)) % 360.0
            r2 = R * R + T * T + H * H
            area = projected_area(ldt["dims"], c, gamma)
            lum = intensity(ldt, c, gamma) / area
            total += lum * lum * (area / r2) / (p * p)
    return total, nx * ny


def background(ldt, phi, room_idx, refl_idx, n, x_h, y_h, H=2.0):
    zones = []
    for z in range(18):
        g = 5 + 10 * z
        mean_i = sum(intensity(ldt, c, g) for c in ldt["c"]) / len(ldt["c"])
        zones.append(mean_i * 2 * math.pi * math.sin(math.radians(g)) * math.radians(10))
    tot = sum(zones)
    f = [x / tot for x in zones]
    down, up = sum(f[:9]), sum(f[9:])
    cum = (sum(f[:4]) + 0.130 * f[4], sum(f[:6]), sum(f[:7]) + 0.547 * f[7], down)
    k = round(x_h * y_h / (x_h + y_h), 2)
    fgl = FGL[min(FGL, key=lambda kk: abs(kk - k))]
    f_df = sum(a * b for a, b in zip(fgl, cum))
    f_dw, f_dc = down - f_df, up
    fw, ww, cw = FT[refl_idx][room_idx]
    e_wid = phi * n / (2 * H * H * (x_h + y_h)) * (f_df * fw + f_dw * ww + f_dc * cw)
    return e_wid / math.pi


def main(path):
    ldt = read_ldt(path)
    phi = flux_lm(ldt)
    for r, (x_h, y_h) in enumerate(ROOMS):
        row = []
        for endwise in (False, True):
            total, n = glare_sum(ldt, phi, x_h, y_h, endwise)
            for f in range(5):
                lb = background(ldt, phi, r, f, n, x_h, y_h)
                row.append(8 * math.log10(0.25 / lb * total))
        print(",".join("%.2f" % v for v in row))


if __name__ == "__main__":
    main(sys.argv[1])
