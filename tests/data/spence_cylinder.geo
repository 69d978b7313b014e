// Spence's problem in plane strain, halves at x >= 0: the 25 mm high cap of a cylinder of
// radius R = 500 (to be given 1000 times the block's stiffness) pressed by a pressure on its
// flat top into a block 3000 wide (in the half) and 3000 deep, so that near the contact (half
// width 2, a / R = 0.004: the surface's slope left out by the linear theory is small) the block
// is a half-plane; the cap starts 1e-4 into the block. 8-node quadrilaterals refined towards
// the contact (h = 0.1 there).
// gmsh -2 -order 2 -format msh41 spence_cylinder.geo -o spence_cylinder.msh
SetFactory("Built-in");
Mesh.SecondOrderIncomplete = 1;
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
R = 500.0; H = 25.0; d = 0.0001;
w = Sqrt(R * R - (R - H) * (R - H));
Point(1) = {0, R - d, 0}; Point(2) = {0, -d, 0}; Point(3) = {w, H - d, 0}; Point(8) = {0, H - d, 0};
Circle(1) = {2, 1, 3}; Line(8) = {3, 8}; Line(2) = {8, 2};
Curve Loop(1) = {1, 8, 2}; Plane Surface(1) = {1};
Point(4) = {0, -3000, 0}; Point(5) = {3000, -3000, 0}; Point(6) = {3000, 0, 0}; Point(7) = {0, 0, 0};
Line(4) = {7, 4}; Line(5) = {4, 5}; Line(6) = {5, 6}; Line(7) = {6, 7};
Curve Loop(2) = {4, 5, 6, 7}; Plane Surface(2) = {2};
Field[1] = Distance; Field[1].PointsList = {2, 7};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = 0.1; Field[2].SizeMax = 300.0; Field[2].DistMin = 2.5; Field[2].DistMax = 3000;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Curve("cap_surface") = {1}; Physical Curve("cap_top") = {8}; Physical Curve("cap_axis") = {2};
Physical Curve("block_axis") = {4}; Physical Curve("block_bottom") = {5}; Physical Curve("block_top") = {7};
Physical Surface("cap") = {1}; Physical Surface("block") = {2};
