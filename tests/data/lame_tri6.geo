// Lame's cylinder section r in [100, 130], z in [0, 10]: unstructured 6-node triangles.
// gmsh -2 -order 2 -format msh41 lame_tri6.geo -o lame_tri6.msh
SetFactory("Built-in");
h = 3.0;
Point(1) = {100, 0, 0, h}; Point(2) = {130, 0, 0, h}; Point(3) = {130, 10, 0, h}; Point(4) = {100, 10, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1}; Physical Curve("outer") = {2}; Physical Curve("top") = {3}; Physical Curve("inner") = {4};
Physical Surface("ring") = {1};
