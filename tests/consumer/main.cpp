// Downstream use of the installed library: the Gabriel graph of a square plus its centre.
#include <constrict/gamma_graph.hpp>
#include <constrict/version.hpp>
#include <cstdio>

int main() {
  constrict::PointSet pts;
  pts.dim = 2;
  pts.coords = {0, 0, 4, 0, 4, 4, 0, 4, 2, 1};
  constrict::GammaFaces g;
  constrict::GraphSpec spec;
  if (!constrict::GraphSpec::from_preset("gabriel", spec)) return 2;
  const constrict::Status s = constrict::build_gamma_graph(pts, spec, g);
  if (!s) {
    std::printf("error: %s\n", s.message().c_str());
    return 1;
  }
  std::printf("constrict %s: %zu Gabriel edges\n", CONSTRICT_VERSION_STRING, g.size());
  return g.size() == 7 ? 0 : 1;
}
