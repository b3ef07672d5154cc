#!/usr/bin/env python3
"""Write the VM18 deck (out-of-plane bending of a curved bar) with N straight
B33 elements on the quarter circle: vm18_deck.py N > deck. The committed
tests/decks/vm18_curved_bar.deck is N = 36; doc/verification.md gives the
convergence of the tip deflection for N = 9, 18, 36, 72 (tests/vm/vm18_convergence.sh)."""
import math
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 36
r = 100.0
print("*HEADING")
print("Ansys Verification Manual VM18, out-of-plane bending of a curved bar")
print("(Timoshenko, Strength of Materials I, p. 412, eq. 241): a quarter of a")
print("horizontal ring, r = 100 in, solid circular section d = 2 in, E = 30e6 psi,")
print("nu = 0.3, built in at A, a vertical load F = 50 lb at the free end B.")
print("Published deflection at B 2.648 in (the formula gives 2.64930); bending")
print("stress 6366 psi and torsional shear 3183 psi at A (M = T = F r). %d straight" % n)
print("B33 elements on the arc: the polygon converges as 1/N^2 (doc/verification.md).")
print("** let: F = 50.0")
print("** let: r = 100.0")
print("** let: E = 30.0e6")
print("** let: G = E/(2*1.3)")
print("** let: I = pi*2.0**4/64")
print("** let: J = 2*I")
print("** let: delta = F*r**3/(E*I)*pi/4 + F*r**3/(G*J)*(3*pi/4 - 2)")
if n == 36:
    print("** expect: displacements step=VM18 substructure=MAIN node=%d u3 == -delta rtol=1e-3" % (n + 1))
    print("** expect: displacements step=VM18 substructure=MAIN node=%d u3 == -2.648 rtol=2e-3" % (n + 1))
    print("** at A the bar carries the moment F r about the radius (torsion) and no")
    print("** bending moment about the tangent; midway both are F r / sqrt 2")
    print("** the reactions at A balance F at B: (r, -r, 0) x (0, 0, F) gives moments F r about")
    print("** X (the bar's axis at A: torsion) and Y (bending); a slender bar (l/i = 314)")
    print("** keeps about 10 digits of equilibrium, hence rtol 1e-8")
    print("** expect: reactions step=VM18 substructure=MAIN node=1 dof=3 force == F rtol=1e-8")
    print("** expect: reactions step=VM18 substructure=MAIN node=1 dof=4 force == F*r rtol=1e-8")
    print("** expect: reactions step=VM18 substructure=MAIN node=1 dof=5 force == F*r rtol=1e-8")
    print("** published stresses at A: bending M c / I = 6366 psi, torsion T c / J = 3183 psi (c = 1)")
    print("** expect: reactions step=VM18 substructure=MAIN node=1 dof=5 force == 6366.0*I rtol=1e-4")
    print("** expect: reactions step=VM18 substructure=MAIN node=1 dof=4 force == 3183.0*J rtol=1e-4")
print("*NODE")
for i in range(n + 1):
    t = 0.5 * math.pi * i / n
    print("%d, %r, %r, 0.0" % (i + 1, r * math.cos(t), r * math.sin(t)))
print("*ELEMENT, TYPE=B33, ELSET=BAR")
for i in range(n):
    print("%d, %d, %d" % (i + 1, i + 1, i + 2))
print("*MATERIAL, NAME=STEEL")
print("*ELASTIC")
print("30.0e6, 0.3")
print("*BEAM SECTION, ELSET=BAR, MATERIAL=STEEL, SECTION=CIRC")
print("1.0")
print("0.0, 0.0, 1.0")
print("*BOUNDARY")
print(" 1, ENCASTRE")
print("*STEP, NAME=VM18")
print("*STATIC")
print("*CLOAD")
print(" %d, 3, -50.0" % (n + 1))
print("*END STEP")
