"""Writes plate_binary.msh and plate_text.msh: the same Gmsh mesh (a 4 x 2 mm plate at
r = 10..14, 8-node quadrilaterals, physical surface "plate", curves "bottom" and "top", point
"corner") saved by Gmsh itself as binary and as text .msh 4.1. Run with the gmsh Python
package (pip install gmsh)."""
import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("plate")
occ = gmsh.model.geo
p = [occ.addPoint(10, 0, 0, 1.0), occ.addPoint(14, 0, 0, 1.0), occ.addPoint(14, 2, 0, 1.0), occ.addPoint(10, 2, 0, 1.0)]
l = [occ.addLine(p[0], p[1]), occ.addLine(p[1], p[2]), occ.addLine(p[2], p[3]), occ.addLine(p[3], p[0])]
loop = occ.addCurveLoop(l)
s = occ.addPlaneSurface([loop])
occ.mesh.setTransfiniteCurve(l[0], 5)
occ.mesh.setTransfiniteCurve(l[2], 5)
occ.mesh.setTransfiniteCurve(l[1], 3)
occ.mesh.setTransfiniteCurve(l[3], 3)
occ.mesh.setTransfiniteSurface(s)
occ.mesh.setRecombine(2, s)
occ.synchronize()
gmsh.model.addPhysicalGroup(2, [s], name="plate")
gmsh.model.addPhysicalGroup(1, [l[0]], name="bottom")
gmsh.model.addPhysicalGroup(1, [l[2]], name="top")
gmsh.model.addPhysicalGroup(0, [p[0]], name="corner")
gmsh.option.setNumber("Mesh.ElementOrder", 2)
gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.option.setNumber("Mesh.Binary", 1)
gmsh.write("plate_binary.msh")
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.write("plate_text.msh")
gmsh.finalize()
