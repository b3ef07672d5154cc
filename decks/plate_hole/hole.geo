// Quarter of a plate with a circular hole (radius R) in a square of half-side W,
// meshed with quadrilaterals for superjoin's gmsh example (decks/plate_hole).
// Export (gmsh 4.8, as committed):
//   gmsh -2 -format inp -setnumber Mesh.SaveGroupsOfNodes -1 -o hole.inp hole.geo
// Only the surface is a physical group, so gmsh writes no line elements; the
// node sets Line1..Line5 are the boundary curves:
//   Line1 y = 0 (R..W), Line2 x = W, Line3 y = W, Line4 x = 0 (W..R), Line5 the hole.
W = 4.0; R = 1.0; hc = 0.08; hf = 0.5;
Point(1) = {0, 0, 0, hc};
Point(2) = {R, 0, 0, hc};
Point(3) = {W, 0, 0, hf};
Point(4) = {W, W, 0, hf};
Point(5) = {0, W, 0, hf};
Point(6) = {0, R, 0, hc};
Line(1) = {2, 3};
Line(2) = {3, 4};
Line(3) = {4, 5};
Line(4) = {5, 6};
Circle(5) = {6, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Recombine Surface {1};
Physical Surface("plate") = {1};
