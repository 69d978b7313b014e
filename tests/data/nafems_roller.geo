// NAFEMS's contact benchmark 1, the 2-D cylinder roller (Konter, Advanced Finite Element
// Contact Benchmarks, NAFEMS 2006), halves at x >= 0: a half disc of diameter 100 touching at
// (0, 0) a block 200 wide (100 in the half) and 200 deep (the disc 0.01 into it); 8-node quadrilaterals refined
// towards the contact (h = 0.3 there: about 20 across the half-width of 6.2).
// gmsh -2 -order 2 -format msh41 nafems_roller.geo -o nafems_roller.msh
SetFactory("Built-in");
Mesh.SecondOrderIncomplete = 1;
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
R = 50.0;
d = 0.01; // the cylinder starts this far into the block, so that contact holds it from the first iteration
Point(1) = {0, R - d, 0}; Point(2) = {0, -d, 0}; Point(3) = {R, R - d, 0}; Point(8) = {0, 2 * R - d, 0};
Circle(1) = {2, 1, 3}; Circle(8) = {3, 1, 8}; Line(2) = {8, 1}; Line(3) = {1, 2};
Curve Loop(1) = {1, 8, 2, 3}; Plane Surface(1) = {1};
Point(4) = {0, -200, 0}; Point(5) = {100, -200, 0}; Point(6) = {100, 0, 0}; Point(7) = {0, 0, 0};
Line(4) = {7, 4}; Line(5) = {4, 5}; Line(6) = {5, 6}; Line(7) = {6, 7};
Curve Loop(2) = {4, 5, 6, 7}; Plane Surface(2) = {2};
Field[1] = Distance; Field[1].PointsList = {2, 7};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = 0.3; Field[2].SizeMax = 15.0; Field[2].DistMin = 7.0; Field[2].DistMax = 100;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Physical Point("cylinder_top") = {8};
Physical Curve("cylinder_surface") = {1, 8}; Physical Curve("cylinder_axis") = {2, 3};
Physical Curve("block_axis") = {4}; Physical Curve("block_bottom") = {5}; Physical Curve("block_top") = {7};
Physical Surface("cylinder") = {1}; Physical Surface("block") = {2};
