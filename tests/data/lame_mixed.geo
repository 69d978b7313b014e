// Lame's cylinder section r in [100, 130], z in [0, 10]: 8-node quadrilaterals below z = 5,
// 6-node triangles above, sharing the nodes of z = 5.
// gmsh -2 -order 2 -format msh41 lame_mixed.geo -o lame_mixed.msh
SetFactory("Built-in");
Mesh.SecondOrderIncomplete = 1;
h = 3.0;
Point(1) = {100, 0, 0, h}; Point(2) = {130, 0, 0, h}; Point(3) = {130, 5, 0, h}; Point(4) = {100, 5, 0, h};
Point(5) = {130, 10, 0, h}; Point(6) = {100, 10, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {3, 5}; Line(6) = {5, 6}; Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7}; Plane Surface(2) = {2};
Transfinite Curve{1, 3} = 11; Transfinite Curve{2, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Physical Curve("bottom") = {1}; Physical Curve("outer") = {2, 5}; Physical Curve("top") = {6}; Physical Curve("inner") = {4, 7};
Physical Surface("quads") = {1}; Physical Surface("triangles") = {2};
