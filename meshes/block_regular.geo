// The paper's scene: block x in [-0.2, 0.2] m, y in [0, 0.002] m,
// regular 1 mm mesh: 400 x 2 transfinite cells recombined into QUA4.
L = 0.2;
H = 0.002;
Point(1) = {-L, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {-L, H, 0};
Line(1) = {1, 2}; // y = 0: the frictional interface
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 401;
Transfinite Curve{2, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("interface") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("block") = {1};
