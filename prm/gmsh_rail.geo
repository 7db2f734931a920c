// The rail of the paper's scene (prm/barboteu_danan_2016_small.prm: 2 m x
// 0.1 m, 32 x 8 cells) as a Gmsh geometry, meshed with quadrilaterals
// (transfinite and recombined: this program needs quadrilaterals in 2D,
// hexahedra in 3D), with named physical groups that prm/gmsh_rail.prm uses
// in its Boundary conditions. A physical group's number is the boundary id
// of its edges; its name can stand for the number.
//
// prm/gmsh_rail.msh (MSH 4.1) and prm/gmsh_rail_msh22.msh (MSH 2.2) were
// made from this file with Gmsh 4.8:
//   gmsh -2 -format msh41 gmsh_rail.geo -o gmsh_rail.msh
//   gmsh -2 -format msh22 gmsh_rail.geo -o gmsh_rail_msh22.msh
// For a free (unstructured) mesh drop the Transfinite lines and keep
// 'Recombine Surface' with 'Mesh.SubdivisionAlgorithm = 1;' (all
// quadrilaterals).

L  = 2;    // length (m)
H  = 0.1;  // height (m)
nx = 32;   // cells along the rail
ny = 8;    // cells across

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {0, H, 0};
Line(1) = {1, 2}; // bottom: on the foundation
Line(2) = {2, 3}; // right end
Line(3) = {3, 4}; // top: the wheel load
Line(4) = {4, 1}; // left end
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Curve("ends", 1)       = {2, 4};
Physical Curve("foundation", 2) = {1};
Physical Curve("load", 3)       = {3};
Physical Surface("rail", 10)    = {1};
