// Reads a STEP file with OpenCASCADE's STEP reader (STEPControl_Reader) and prints, as JSON,
// every edge of the transferred shape sampled at 65 points of its 3D curve, and the read time.
// Used by tests/step_occt.rs to check that OCCT reads the curves `--step-out` writes; how it is
// built is in README.md here.
// usage: occt_read_curves FILE.step
#include <BRep_Tool.hxx>
#include <Geom_Curve.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <chrono>
#include <cstdio>

int main(int argc, char** argv) {
  if (argc < 2) { std::fprintf(stderr, "usage: %s FILE.step\n", argv[0]); return 2; }
  auto t0 = std::chrono::steady_clock::now();
  STEPControl_Reader r;
  if (r.ReadFile(argv[1]) != IFSelect_RetDone) { std::printf("{\"error\": \"ReadFile failed\"}\n"); return 1; }
  r.TransferRoots();
  TopoDS_Shape s = r.OneShape();
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"read_ms\": %.6g, \"edges\": [", ms);
  bool first = true;
  for (TopExp_Explorer ex(s, TopAbs_EDGE); ex.More(); ex.Next()) {
    Standard_Real a, b;
    Handle(Geom_Curve) c = BRep_Tool::Curve(TopoDS::Edge(ex.Current()), a, b);
    if (c.IsNull()) continue;
    std::printf("%s{\"type\": \"%s\", \"range\": [%.17g, %.17g], \"points\": [", first ? "" : ", ",
                c->DynamicType()->Name(), a, b);
    first = false;
    for (int k = 0; k <= 64; ++k) {
      gp_Pnt p = c->Value(a + (b - a) * k / 64.0);
      std::printf("%s[%.17g, %.17g, %.17g]", k ? ", " : "", p.X(), p.Y(), p.Z());
    }
    std::printf("]}");
  }
  std::printf("]}\n");
  return 0;
}
