// Small test mesh: a 4 mm x 2 mm block, mixed TRI3/QUA4, a 0D physical group and a
// second surface so the element sets differ; saved with parametric node coordinates.
Point(1) = {0, 0, 0, 1e-3};
Point(2) = {0.004, 0, 0, 1e-3};
Point(3) = {0.004, 0.002, 0, 1e-3};
Point(4) = {0, 0.002, 0, 1e-3};
Point(5) = {0.002, 0, 0, 1e-3};
Point(6) = {0.002, 0.002, 0, 1e-3};
Line(1) = {1, 5};
Line(2) = {5, 2};
Line(3) = {2, 3};
Line(4) = {3, 6};
Line(5) = {6, 4};
Line(6) = {4, 1};
Line(7) = {5, 6};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Mesh.RecombinationAlgorithm = 0;
Recombine Surface{2};
Mesh.SaveParametric = 1;
Physical Curve("interface") = {1, 2};
Physical Curve("top") = {4, 5};
Physical Curve(7) = {7};
Physical Point("corner") = {1};
Physical Surface("left_part") = {1};
Physical Surface("block") = {1, 2};
