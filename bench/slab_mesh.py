"""The mesh shared by bench/gen_twins.py and bench/gen_modules.py: a square S4
slab of m x m elements (nodes 1..(m+1)^2, row by row) on four B33 columns whose
feet are the next four nodes, each standing under one slab corner."""


def corners_and_feet(m):
    """The slab corner nodes (counter-clockwise from the origin) and the feet under them."""
    n1 = m + 1
    return [1, n1, n1 * n1, n1 * (n1 - 1) + 1], [n1 * n1 + k for k in range(1, 5)]


def slab_and_columns(m):
    """The *ELEMENT cards: ELSET=SLAB (S4, elements 1..m^2), ELSET=COLUMNS (B33, the next four)."""
    n1 = m + 1
    corners, feet = corners_and_feet(m)
    out = ["*ELEMENT, TYPE=S4, ELSET=SLAB"]
    for j in range(m):
        for i in range(m):
            a = j * n1 + i + 1
            out.append(f"{j * m + i + 1}, {a}, {a + 1}, {a + n1 + 1}, {a + n1}")
    out.append("*ELEMENT, TYPE=B33, ELSET=COLUMNS")
    for k, (f, c) in enumerate(zip(feet, corners)):
        out.append(f"{m * m + k + 1}, {f}, {c}")
    return out
