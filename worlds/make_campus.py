#!/usr/bin/env python3
"""Writes campus.yaml: an outdoor campus of about 200 m x 150 m, streets between building
blocks, open spaces and sparse street furniture, for a long-range (80 m) laser (issue
"Maps that close at any scale").

  y ^
150 |  . . . fence, gaps . . . . . . . . . . . . . . . . . . . . . .
    |  AN=========+=BN=======================+=CN==================+ DN    north street, 8 m
    |  |  +-----+ |  square:  . tree          |  +---+   +-------+  |
    |  |  | lab |_|  o fountain   - bench    |  |lib|   | gym   |  |
    |  |  +--+  ___|  . tree   - bench  .    |  +---+   +--. .--+  |
 76 |  AM=========+=BM=======================+=CM==================+ DM    middle street, 12 m
    |  |  +--------+  parking lot:           |  +----------+      |
    |  |  | hall   |  o pole  o pole  [car]   |  |  L-shaped|  +-+ |
    |  |  +--+  +--+  o pole  - - - fence     |  +--+  +---+  +-+ |
  7 |  AS===gate==+=BS=======================+=CS==================+ DS    south street, 10 m
    +--+----------+-------------------------+----------------------+--> x
       8          70                         132                   192
 west street 9 m, B street 11 m, C street 8 m, east street 10 m (centre lines at x).

Six blocks between the streets: four with buildings (solid polygons with irregular
outlines: wings, notches, a chamfered corner, a slanted facade; no two alike), a parking
lot (light poles, a kiosk, parked cars as boxes, one of which leaves) and a square (a
fountain, trees, benches). Along the streets: trees and bollards (small polygons) at
irregular spacing on the sidewalks, short wall segments, and fences as polylines with
gaps. Beyond the outer streets there is little: a broken site fence on the west and north.
Seen with an 80 m laser the returns are sparse: facades in places, poles and trees
elsewhere, nothing at all in most beams over the open spaces.
Places: every street crossing (AS .. DN, x index A-D, y index S/M/N) and `gate`, the
middle of the south street between AS and BS. The roadmap is the street grid between
them. Loops: around one block about 262 m (e.g. gate BS BM AM AS gate), around two
blocks about 390 m, around the whole site about 650 m.
Run: python3 worlds/make_campus.py > worlds/campus.yaml"""

# Street centre lines (m) and widths (m).
XS = {"A": (8.0, 9.0), "B": (70.0, 11.0), "C": (132.0, 8.0), "D": (192.0, 10.0)}
YS = {"S": (7.0, 10.0), "M": (76.0, 12.0), "N": (143.0, 8.0)}
GATE = (39.0, 7.0)


def pt(p):
    return f"[{round(p[0], 3):g}, {round(p[1], 3):g}]"


def shift(points, dx, dy):
    return [(x + dx, y + dy) for x, y in points]


def square(cx, cy, s):
    h = s / 2
    return [(cx - h, cy - h), (cx + h, cy - h), (cx + h, cy + h), (cx - h, cy + h)]


def octagon(cx, cy, r):
    k = 0.4142 * r  # half side of a regular octagon of inradius r
    return [(cx + k, cy - r), (cx + r, cy - k), (cx + r, cy + k), (cx + k, cy + r),
            (cx - k, cy + r), (cx - r, cy + k), (cx - r, cy - k), (cx - k, cy - r)]


# Buildings: counter-clockwise outlines in block coordinates (origin at the block's
# south-west corner, i.e. the corner of the sidewalks), shifted into place below.
# Block (A-B, S-M), x 12.5 .. 64.5, y 12 .. 70: "hall", a long block with a notch and
# an entrance wing, and a small pavilion.
HALL = [(4, 5), (30, 5), (30, 3), (38, 3), (38, 5), (46, 5), (46, 24), (41, 24), (41, 31),
        (46, 31), (46, 40), (22, 40), (22, 36), (16, 36), (16, 40), (4, 40), (4, 27),
        (2, 27), (2, 19), (4, 19)]
PAVILION = [(8, 47), (19, 47), (21, 50), (21, 54), (8, 54)]  # chamfered corner
# Block (C-D, S-M), x 136 .. 187, y 12 .. 70: an L-shaped building and an annex.
LSHAPE = [(3, 4), (36, 4), (36, 17), (19, 17), (19, 33), (23, 33), (23, 46), (3, 46),
          (3, 30), (1, 30), (1, 24), (3, 24)]
ANNEX = [(41, 30), (48, 30), (48, 52), (41, 52), (41, 45), (39, 45), (39, 38), (41, 38)]
# Block (A-B, M-N), x 12.5 .. 64.5, y 82 .. 139: "lab", with a courtyard open to the east
# and a slanted south facade.
LAB = [(5, 6), (40, 3), (40, 20), (28, 20), (28, 34), (44, 34), (44, 52), (20, 52),
       (20, 49), (5, 49), (5, 30), (8, 30), (8, 22), (5, 22)]
# Block (C-D, M-N), x 136 .. 187, y 82 .. 139: library and gym.
LIBRARY = [(4, 8), (17, 8), (17, 5), (25, 5), (25, 8), (27, 8), (27, 44), (15, 44),
           (15, 48), (9, 48), (9, 44), (4, 44)]
GYM = [(34, 12), (48, 12), (48, 31), (45, 31), (45, 37), (48, 37), (48, 50), (34, 50),
       (34, 40), (36, 40), (36, 23), (34, 23)]


def block(xa, xb, ya, yb):
    """Corners of the block between streets xa, xb (west, east) and ya, yb (south, north)."""
    x0 = XS[xa][0] + XS[xa][1] / 2
    x1 = XS[xb][0] - XS[xb][1] / 2
    y0 = YS[ya][0] + YS[ya][1] / 2
    y1 = YS[yb][0] - YS[yb][1] / 2
    return x0, y0, x1, y1


def along_x(y, xs, size):
    return [square(x, y, size) for x in xs]


def along_y(x, ys, size):
    return [square(x, y, size) for y in ys]


def main():
    print("# Campus, about 200 m x 150 m outdoors: streets between six blocks (four built, a "
          "parking lot, a square), loops of 260-650 m; generated by make_campus.py (edit "
          "that, not this).")
    print("clearance_m: 0.4")
    walls = []  # (kind, points, comment)

    def poly(points, comment):
        walls.append(("polygon", points, comment))

    def line(points, comment):
        walls.append(("polyline", points, comment))

    # Buildings.
    bx, by, _, _ = block("A", "B", "S", "M")
    poly(shift(HALL, bx, by), "building: hall")
    poly(shift(PAVILION, bx, by), "building: pavilion")
    bx, by, _, _ = block("C", "D", "S", "M")
    poly(shift(LSHAPE, bx, by), "building: L-shaped")
    poly(shift(ANNEX, bx, by), "building: annex")
    bx, by, _, _ = block("A", "B", "M", "N")
    poly(shift(LAB, bx, by), "building: lab")
    bx, by, _, _ = block("C", "D", "M", "N")
    poly(shift(LIBRARY, bx, by), "building: library")
    poly(shift(GYM, bx, by), "building: gym")

    # Parking lot, block (B-C, S-M), x 75.5 .. 128, y 12 .. 70: light poles on an
    # irregular grid, a kiosk, a low fence with gaps along its north side, a short wall.
    px, py, px1, py1 = block("B", "C", "S", "M")
    for (x, y) in [(8, 9), (27, 10), (45, 8), (9, 31), (30, 29), (47, 33), (18, 50), (41, 52)]:
        poly(square(px + x, py + y, 0.3), "light pole")
    poly([(px + 33, py + 18), (px + 37, py + 18), (px + 37, py + 21), (px + 33, py + 21)],
         "kiosk")
    fy = py1 - 1.5
    for x0, x1 in [(px + 2, px + 14), (px + 18, px + 31), (px + 36, px + 49)]:
        line([(x0, fy), (x1, fy)], "parking fence")
    line([(px1 - 1.0, py + 4), (px1 - 1.0, py + 15)], "short wall")

    # Square, block (B-C, M-N), x 75.5 .. 128, y 82 .. 139: a fountain, trees, benches.
    sx, sy, sx1, sy1 = block("B", "C", "M", "N")
    poly(octagon(sx + 26, sy + 29, 2.5), "fountain")
    for (x, y) in [(9, 12), (17, 44), (40, 15), (44, 41), (31, 50)]:
        poly(octagon(sx + x, sy + y, 0.35), "tree")
    line([(sx + 20, sy + 22), (sx + 22.5, sy + 22)], "bench")
    line([(sx + 33, sy + 34), (sx + 33, sy + 36.5)], "bench")
    line([(sx + 12, sy + 30), (sx + 14.5, sy + 31)], "bench")

    # Sidewalk furniture along the streets, at irregular spacing, 3-6 m off the centre
    # lines (the driven lines): trees (octagons), bollards (squares).
    s_y, s_w = YS["S"]
    for p in along_x(s_y + s_w / 2 + 1.0, [18, 31, 52, 61, 84, 103, 119, 141, 158, 177], 0.3):
        poly(p, "bollard")
    for p in along_x(s_y - s_w / 2 - 1.0, [25, 47, 96, 150, 171], 0.3):
        poly(p, "bollard")
    m_y, m_w = YS["M"]
    for x in [20, 44, 59, 88, 112, 146, 163, 181]:
        poly(octagon(x, m_y - m_w / 2 + 1.2, 0.35), "tree")
    for x in [28, 97, 121, 155, 176]:
        poly(octagon(x, m_y + m_w / 2 - 1.2, 0.35), "tree")
    n_y, n_w = YS["N"]
    for x in [23, 51, 93, 139, 168]:
        poly(octagon(x, n_y - n_w / 2 - 1.0, 0.3), "tree")
    b_x, b_w = XS["B"]
    for y in [21, 38, 55, 95, 119]:
        poly(square(b_x - b_w / 2 + 1.0, y, 0.3), "bollard")
    for y in [30, 63, 104, 131]:
        poly(square(b_x + b_w / 2 - 1.0, y, 0.3), "bollard")
    c_x, c_w = XS["C"]
    for y in [26, 49, 91, 126]:
        poly(octagon(c_x + c_w / 2 + 1.0, y, 0.3), "tree")
    a_x, a_w = XS["A"]
    for y in [33, 58, 101, 124]:
        poly(square(a_x + a_w / 2 + 0.8, y, 0.3), "bollard")
    d_x, d_w = XS["D"]
    for y in [19, 44, 97, 118, 135]:
        poly(octagon(d_x - d_w / 2 - 1.0, y, 0.3), "tree")
    # Short walls: a bus shelter on the middle street, a low wall at the gym.
    line([(100, m_y + m_w / 2 + 0.5), (104, m_y + m_w / 2 + 0.5)], "bus shelter")
    line([(177, 88), (183, 88), (183, 91)], "low wall")

    # Site fence, with gaps, west of the west street and north of the north street.
    fx = a_x - a_w / 2 - 1.5
    for y0, y1 in [(2, 30), (36, 71), (84, 120), (127, 146)]:
        line([(fx, y0), (fx, y1)], "site fence")
    fy = n_y + n_w / 2 + 1.5
    for x0, x1 in [(2, 40), (48, 66), (80, 125), (140, 199)]:
        line([(x0, fy), (x1, fy)], "site fence")

    print("walls:")
    for kind, points, comment in walls:
        print(f"  - {kind}: [{', '.join(pt(p) for p in points)}]  # {comment}")
    print("boxes:")  # parked cars, one leaves and comes back
    print(f"  - {{name: car_a, center: {pt((px + 14, py + 20))}, size: [4.4, 1.8]}}")
    print(f"  - {{name: car_b, center: {pt((px + 22, py + 40))}, size: [4.6, 1.9], "
          f"moves: [{{t_s: 1500, center: {pt((px + 22, py + 44))}}}, "
          f"{{t_s: 4200, center: {pt((px + 40, py + 42))}}}]}}")
    print(f"  - {{name: van, center: {pt((px + 42, py + 22))}, size: [5.2, 2.0]}}")
    print("places:")  # the street crossings and the gate
    names = []
    for yk, (y, _) in YS.items():
        for xk, (x, _) in XS.items():
            names.append(xk + yk)
            print(f"  - {{name: {xk + yk}, at: {pt((x, y))}}}")
    print(f"  - {{name: gate, at: {pt(GATE)}}}")
    print("roadmap:")
    xk, yk = list(XS), list(YS)
    for y in yk:
        for a, b in zip(xk, xk[1:]):
            if (a, b, y) == ("A", "B", "S"):
                print("  - [AS, gate]")
                print("  - [gate, BS]")
            else:
                print(f"  - [{a + y}, {b + y}]")
    for x in xk:
        for a, b in zip(yk, yk[1:]):
            print(f"  - [{x + a}, {x + b}]")


if __name__ == "__main__":
    main()
