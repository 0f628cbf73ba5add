// The paper's block, unstructured and quad-dominant: size 0.25 mm at the ends, 1 mm in the
// middle; the simple recombination leaves some triangles, so the mesh mixes QUA4 and TRI3.
L = 0.2;
H = 0.002;
Point(1) = {-L, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {-L, H, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = MathEval;
Field[1].F = "0.00025 + 0.00075 * (1 - Fabs(x) / 0.2)";
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.Algorithm = 6;
Mesh.RecombinationAlgorithm = 0;
Recombine Surface{1};
Physical Curve("interface") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("block") = {1};
