// written for gmsh 4.8.4 (Debian 12): gmsh -3 box2.geo -o box2.inp -format inp
SetFactory("OpenCASCADE");
Box(1) = {0,0,0, 10,1,1};
Mesh.ElementOrder = 2;
Mesh.CharacteristicLengthMax = 0.7;
Mesh.SaveGroupsOfNodes = 1;
Physical Volume("SOLID") = {1};
Physical Surface("FIX") = {1};
Physical Surface("TIP") = {2};
