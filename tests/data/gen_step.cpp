// Writes the STEP test files of tests/data/ with OpenCASCADE's STEP writer (see README.md here).
// usage: gen_step OUTDIR [big]
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopoDS_Compound.hxx>
#include <Geom_Plane.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>
#include <cstdio>
#include <string>

static int write(const TopoDS_Shape& s, const std::string& path) {
  STEPControl_Writer w;
  if (w.Transfer(s, STEPControl_AsIs) != IFSelect_RetDone) return 1;
  if (w.Write(path.c_str()) != IFSelect_RetDone) return 1;
  std::printf("wrote %s\n", path.c_str());
  return 0;
}

// The first face of a shape whose surface is not a plane (the lateral face of a cylinder/cone).
static TopoDS_Face curvedFace(const TopoDS_Shape& s) {
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) {
    TopoDS_Face f = TopoDS::Face(ex.Current());
    if (!BRep_Tool::Surface(f)->IsKind(STANDARD_TYPE(Geom_Plane))) return f;
  }
  return TopoDS_Face();
}

int main(int argc, char** argv) {
  std::string d = argc > 1 ? argv[1] : ".";
  Interface_Static::SetCVal("write.step.schema", "AP214IS");
  gp_Ax2 z(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1));
  int bad = 0;
  // A unit sphere about the origin (SPHERICAL_SURFACE), and the same sphere as a rational
  // B-spline surface (the complex B_SPLINE_SURFACE_WITH_KNOTS / RATIONAL_B_SPLINE_SURFACE entity).
  TopoDS_Shape sphere = BRepPrimAPI_MakeSphere(z, 1.0).Face();
  bad += write(sphere, d + "/occt_sphere.step");
  bad += write(BRepBuilderAPI_NurbsConvert(sphere).Shape(), d + "/occt_sphere_nurbs.step");
  // The plane z = 1/4, a square face [-3, 3]^2.
  gp_Pln pl(gp_Pnt(0, 0, 0.25), gp_Dir(0, 0, 1));
  bad += write(BRepBuilderAPI_MakeFace(pl, -3, 3, -3, 3).Face(), d + "/occt_plane.step");
  // The plane y = 0 through the z axis, the face x in [-3, 3], z in [-3/4, 3/4] (its frame's
  // x direction along x, so its y direction is -z): it cuts the cylinder below along its seam
  // (x = 1) and its half-turn line (x = -1), and the torus along two tube circles.
  gp_Pln xz(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0), gp_Dir(1, 0, 0)));
  bad += write(BRepBuilderAPI_MakeFace(xz, -3, 3, -0.75, 0.75).Face(), d + "/occt_plane_xz.step");
  // A torus, major radius 2, minor 1/2, about the z axis (TOROIDAL_SURFACE).
  bad += write(BRepPrimAPI_MakeTorus(z, 2.0, 0.5).Face(), d + "/occt_torus.step");
  // The lateral faces of a cylinder (radius 1, z in [-1, 1]) and of a cone (radius 1 at z = 0,
  // 1/2 at z = 1).
  gp_Ax2 low(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1));
  bad += write(curvedFace(BRepPrimAPI_MakeCylinder(low, 1.0, 2.0).Shape()), d + "/occt_cylinder.step");
  bad += write(curvedFace(BRepPrimAPI_MakeCone(z, 1.0, 0.5, 1.0).Shape()), d + "/occt_cone.step");
  // A solid cube [-0.7, 0.7]^3: six PLANE faces sharing their edges (a closed shell).
  bad += write(BRepPrimAPI_MakeBox(gp_Pnt(-0.7, -0.7, -0.7), 1.4, 1.4, 1.4).Shape(), d + "/occt_box.step");
  // An assembly: a compound of two unit spheres as rational B-splines, about (0, 0, 0) and
  // (1.5, 0, 0); OCCT writes each as a part placed by an ITEM_DEFINED_TRANSFORMATION (identity).
  TopoDS_Compound two;
  BRep_Builder builder;
  builder.MakeCompound(two);
  builder.Add(two, BRepBuilderAPI_NurbsConvert(sphere).Shape());
  gp_Ax2 right(gp_Pnt(1.5, 0, 0), gp_Dir(0, 0, 1));
  builder.Add(two, BRepBuilderAPI_NurbsConvert(BRepPrimAPI_MakeSphere(right, 1.0).Face()).Shape());
  bad += write(two, d + "/occt_two_spheres.step");
  // With a second argument `big` (not kept in the repository, 0.9 MB): 200 unit spheres as
  // rational B-splines on a 10 x 20 grid of spacing 3 at z = 5, for timing the readers.
  if (argc > 2 && std::string(argv[2]) == "big") {
    TopoDS_Compound many;
    builder.MakeCompound(many);
    for (int i = 0; i < 200; ++i) {
      gp_Ax2 at(gp_Pnt(3.0 * (i % 10), 3.0 * (i / 10), 5.0), gp_Dir(0, 0, 1));
      builder.Add(many, BRepBuilderAPI_NurbsConvert(BRepPrimAPI_MakeSphere(at, 1.0).Face()).Shape());
    }
    bad += write(many, d + "/occt_200_spheres.step");
  }
  return bad;
}
