// A brick cantilever 0.4 x 0.04 x 0.04 m along x, meshed by Gmsh with 8 x 2 x 2 hexahedra
// (structured extrusion), for flexstress's Gmsh import test: the same bricks as flexstress's
// own add_box_mesh, numbered and ordered Gmsh's way. Physical groups: the clamped root face,
// the loaded tip face, a read-out line along the top edge, the volume.
L = 0.4;
B = 0.04;
H = 0.04;
Point(1) = {0, -B / 2, -H / 2};
edge[] = Extrude {L, 0, 0} { Point{1}; Layers{8}; };
face[] = Extrude {0, B, 0} { Curve{edge[1]}; Layers{2}; Recombine; };
body[] = Extrude {0, 0, H} { Surface{face[1]}; Layers{2}; Recombine; };
e = 1e-6;
Physical Volume("body") = {body[1]};
Physical Surface("root") = Surface In BoundingBox {-e, -B, -H, e, B, H};
Physical Surface("tip") = Surface In BoundingBox {L - e, -B, -H, L + e, B, H};
Physical Curve("top edge") = Curve In BoundingBox {-e, B / 2 - e, H / 2 - e, L + e, B / 2 + e, H / 2 + e};
Mesh.MshFileVersion = 4.1;
