// The paper's block graded towards both ends: ~0.1 mm elements at x = +-0.2 m growing
// geometrically to ~2 mm at x = 0, 4 elements through the thickness, QUA4.
// Each half is its own transfinite surface so the progression runs end -> middle.
L = 0.2;
H = 0.002;
N = 316;       // points per half: 315 elements
r = 1.009596;  // 1e-4 * r^314 ~ 2e-3 and the sizes add up to L
Point(1) = {-L, 0, 0};
Point(2) = {0, 0, 0};
Point(3) = {L, 0, 0};
Point(4) = {-L, H, 0};
Point(5) = {0, H, 0};
Point(6) = {L, H, 0};
Line(1) = {1, 2}; // interface, left half
Line(2) = {2, 3}; // interface, right half
Line(3) = {4, 5}; // top, left half
Line(4) = {5, 6}; // top, right half
Line(5) = {1, 4}; // left
Line(6) = {2, 5}; // middle
Line(7) = {3, 6}; // right
Curve Loop(1) = {1, 6, -3, -5};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 7, -4, -6};
Plane Surface(2) = {2};
Transfinite Curve{1, 3} = N Using Progression r;
Transfinite Curve{2, 4} = N Using Progression 1/r;
Transfinite Curve{5, 6, 7} = 5;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
Physical Curve("interface") = {1, 2};
Physical Curve("top") = {3, 4};
Physical Curve("left") = {5};
Physical Curve("right") = {7};
Physical Surface("block") = {1, 2};
