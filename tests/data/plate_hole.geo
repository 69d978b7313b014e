// Kirsch's plate: a quarter of a square plate, half-width 25 a, with a hole of radius a = 1
// at the origin; 8-node quadrilaterals graded towards the hole.
// gmsh -2 -order 2 -format msh41 plate_hole.geo -o plate_hole.msh
SetFactory("Built-in");
Mesh.SecondOrderIncomplete = 1;
a = 1.0; L = 25.0;
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {L, 0, 0}; Point(4) = {L, L, 0};
Point(5) = {0, L, 0}; Point(6) = {0, a, 0}; Point(7) = {a / Sqrt(2), a / Sqrt(2), 0};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 6};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 2}; Line(7) = {7, 4};
Curve Loop(1) = {1, 2, -7, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {7, 3, 4, 5}; Plane Surface(2) = {2};
Transfinite Curve{1, 7, -4} = 31 Using Progression 1.15;
Transfinite Curve{2, 6, 3, 5} = 13;
Transfinite Surface{1} = {2, 3, 4, 7}; Transfinite Surface{2} = {7, 4, 5, 6};
Recombine Surface{1, 2};
Physical Curve("bottom") = {1}; Physical Curve("right") = {2}; Physical Curve("top") = {3};
Physical Curve("left") = {4}; Physical Curve("hole") = {5, 6};
Physical Surface("plate") = {1, 2};
