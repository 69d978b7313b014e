// Hertz's cylinder on a flat block in plane strain, halves at x >= 0: a quarter disc of
// radius R = 10 touching at (0, -10) a block 30 wide and 20 deep; 8-node quadrilaterals
// refined towards the contact (h = 0.03 there).
// gmsh -2 -order 2 -format msh41 hertz_cylinder.geo -o hertz_cylinder.msh
SetFactory("Built-in");
Mesh.SecondOrderIncomplete = 1;
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
R = 10.0;
Point(1) = {0, 0, 0}; Point(2) = {0, -R, 0}; Point(3) = {R, 0, 0};
Circle(1) = {2, 1, 3}; Line(2) = {3, 1}; Line(3) = {1, 2};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Point(4) = {0, -R - 20, 0}; Point(5) = {30, -R - 20, 0}; Point(6) = {30, -R, 0}; Point(7) = {0, -R, 0};
Line(4) = {7, 4}; Line(5) = {4, 5}; Line(6) = {5, 6}; Line(7) = {6, 7};
Curve Loop(2) = {4, 5, 6, 7}; Plane Surface(2) = {2};
Field[1] = Distance; Field[1].PointsList = {2, 7};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = 0.04; Field[2].SizeMax = 3.0; Field[2].DistMin = 0.8; Field[2].DistMax = 12;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Curve("cylinder_surface") = {1}; Physical Curve("cylinder_top") = {2}; Physical Curve("cylinder_axis") = {3};
Physical Curve("block_axis") = {4}; Physical Curve("block_bottom") = {5}; Physical Curve("block_top") = {7};
Physical Surface("cylinder") = {1}; Physical Surface("block") = {2};
