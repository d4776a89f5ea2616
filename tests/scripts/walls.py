"""Made-up 2D worlds for the analysis scripts' tests: walls as segments, and the range a
beam meets them at."""
import math


def box(x, y, side):
    """The four walls of a square post with its lower left corner at (x, y)."""
    return [(x, y, x + side, y), (x + side, y, x + side, y + side),
            (x + side, y + side, x, y + side), (x, y + side, x, y)]


def cast(walls, x, y, a, max_range=30.0):
    """Range of the nearest wall (x0, y0, x1, y1) along heading a from (x, y)."""
    best = max_range
    dx, dy = math.cos(a), math.sin(a)
    for x0, y0, x1, y1 in walls:
        ex, ey = x1 - x0, y1 - y0
        det = ex * dy - ey * dx
        if abs(det) < 1e-12:
            continue
        t = (ex * (y0 - y) - ey * (x0 - x)) / det  # along the ray
        u = (dx * (y0 - y) - dy * (x0 - x)) / det  # along the wall
        if t > 0 and 0 <= u <= 1:
            best = min(best, t)
    return best
