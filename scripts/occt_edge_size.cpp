// How many poles OpenCASCADE's own intersection curves have: GeomInt_IntSS::Perform (3D curves
// approximated, no p-curves, as GeomAPI_IntSS does) on every pair of a scene, once, then per line
// its B-spline's pole count, degree and distinct knots. Used by scripts/edge_size_table.py to
// compare the size of ssitrace's certified edges with OCCT's uncertified curves.
//
// usage: occt_edge_size SCENE.txt [tol=1e-7]   (SCENE.txt: ../shared/peers/scene2txt.py output)
// stdout: {"tol": .., "tol_reached_3d": .., "lines": [{"pair": [i, j], "poles": n, "degree": d,
//          "knots": k}, ...]}; a line that is not a B-spline has "poles": null.
#include <GeomInt_IntSS.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

typedef std::vector<Handle(Geom_Surface)> Surfaces;

static void fail(const char* why) {
  fprintf(stderr, "occt_edge_size: %s\n", why);
  exit(2);
}

// nu x nv points "x y z w" (w = weight, the point not multiplied by it); true if any w != 1.
static bool readNet(FILE* f, int nu, int nv, TColgp_Array2OfPnt& pts, TColStd_Array2OfReal& w) {
  bool rational = false;
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      double x, y, z, wt;
      if (fscanf(f, "%lf %lf %lf %lf", &x, &y, &z, &wt) != 4) fail("a control point is malformed");
      pts(i, j) = gp_Pnt(x, y, z);
      w(i, j) = wt;
      rational = rational || wt != 1.0;
    }
  return rational;
}

static Handle(Geom_Surface) bezier(FILE* f, int m, int n) {
  TColgp_Array2OfPnt pts(1, m + 1, 1, n + 1);
  TColStd_Array2OfReal w(1, m + 1, 1, n + 1);
  readNet(f, m + 1, n + 1, pts, w);
  return new Geom_BezierSurface(pts, w);
}

// A flat knot vector as distinct values and multiplicities.
static void distinct(const std::vector<double>& flat, std::vector<double>& k, std::vector<int>& m) {
  for (double t : flat) {
    if (!k.empty() && k.back() == t) {
      m.back() += 1;
    } else {
      k.push_back(t);
      m.push_back(1);
    }
  }
}

static Handle(Geom_Surface) nurbs(FILE* f) {
  int p, q, nu, nv;
  if (fscanf(f, "%d %d %d %d", &p, &q, &nu, &nv) != 4) fail("a NURBS header is malformed");
  std::vector<double> fu(nu + p + 1), fv(nv + q + 1);
  for (double& t : fu)
    if (fscanf(f, "%lf", &t) != 1) fail("a u knot is malformed");
  for (double& t : fv)
    if (fscanf(f, "%lf", &t) != 1) fail("a v knot is malformed");
  TColgp_Array2OfPnt pts(1, nu, 1, nv);
  TColStd_Array2OfReal w(1, nu, 1, nv);
  bool rational = readNet(f, nu, nv, pts, w);
  std::vector<double> ku, kv;
  std::vector<int> mu, mv;
  distinct(fu, ku, mu);
  distinct(fv, kv, mv);
  TColStd_Array1OfReal KU(1, (int)ku.size()), KV(1, (int)kv.size());
  TColStd_Array1OfInteger MU(1, (int)mu.size()), MV(1, (int)mv.size());
  for (size_t i = 0; i < ku.size(); ++i) KU((int)i + 1) = ku[i], MU((int)i + 1) = mu[i];
  for (size_t i = 0; i < kv.size(); ++i) KV((int)i + 1) = kv[i], MV((int)i + 1) = mv[i];
  if (rational) return new Geom_BSplineSurface(pts, w, KU, KV, MU, MV, p, q);
  return new Geom_BSplineSurface(pts, KU, KV, MU, MV, p, q);
}

// "side K" then K surfaces ("bezier m n" + net, or "nurbs p q nu nv" + knots + net).
static Surfaces side(FILE* f) {
  int k;
  if (fscanf(f, " side %d", &k) != 1) fail("a side header is malformed");
  Surfaces s;
  for (int i = 0; i < k; ++i) {
    char kind[16];
    if (fscanf(f, "%15s", kind) != 1) fail("a surface kind is missing");
    if (!strcmp(kind, "bezier")) {
      int m, n;
      if (fscanf(f, "%d %d", &m, &n) != 2) fail("a Bezier header is malformed");
      s.push_back(bezier(f, m, n));
    } else if (!strcmp(kind, "nurbs")) {
      s.push_back(nurbs(f));
    } else {
      fail("unknown surface kind");
    }
  }
  return s;
}

int main(int argc, char** argv) {
  if (argc < 2) fail("usage: occt_edge_size SCENE.txt [tol]");
  FILE* f = fopen(argv[1], "r");
  if (!f) fail("cannot open the scene");
  double tol = argc > 2 ? atof(argv[2]) : 1e-7;
  Surfaces a, b;
  char head[16] = "";
  if (fscanf(f, "%15s", head) == 1 && !strcmp(head, "ssi-scene")) {
    int version;
    if (fscanf(f, "%d", &version) != 1 || version != 2) fail("unsupported ssi-scene version");
    a = side(f);
    b = side(f);
  } else {  // two Bezier surfaces, each "m n" + net
    rewind(f);
    int m, n;
    if (fscanf(f, "%d %d", &m, &n) != 2) fail("a Bezier header is malformed");
    a.push_back(bezier(f, m, n));
    if (fscanf(f, "%d %d", &m, &n) != 2) fail("a Bezier header is malformed");
    b.push_back(bezier(f, m, n));
  }
  fclose(f);
  double reached = 0;
  printf("{\"tol\": %g, \"lines\": [", tol);
  bool first = true;
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) {
      GeomInt_IntSS ss;
      try {
        ss.Perform(a[i], b[j], tol, Standard_True, Standard_False, Standard_False);
      } catch (Standard_Failure const&) {
        continue;
      }
      if (!ss.IsDone()) continue;
      if (ss.TolReached3d() > reached) reached = ss.TolReached3d();
      for (int l = 1; l <= ss.NbLines(); ++l) {
        Handle(Geom_BSplineCurve) c = Handle(Geom_BSplineCurve)::DownCast(ss.Line(l));
        printf("%s{\"pair\": [%zu, %zu], ", first ? "" : ", ", i, j);
        if (c.IsNull())
          printf("\"poles\": null}");
        else
          printf("\"poles\": %d, \"degree\": %d, \"knots\": %d}", c->NbPoles(), c->Degree(), c->NbKnots());
        first = false;
      }
    }
  printf("], \"tol_reached_3d\": %g}\n", reached);
  return 0;
}
