// Several Ipopt solves per rank under `mpirun -np 2`, with results exchanged
// between the ranks. It guards the trap of this stack: Debian's MUMPS (inside
// Ipopt) ships a fake sequential MPI (libmpiseq) defining MPI_Init,
// MPI_Comm_rank, ...; it coexists with Open MPI only if the executable links
// libmpi's C bindings itself and MPI calls stay outside Ipopt solves.
//
// Each rank solves one_robot_axis at three horizons of its own (steps 10 + rank
// + 2k) and one shared instance (steps 12). All results are gathered on every
// rank: each must be solved and within 2 % of the closed-form bound, and the
// shared instance must give the same T_f bit for bit on both ranks.
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/config/settings.h"
#include "core/config/solver_settings.h"
#include "core/model/scene_yaml.h"
#include "search/solve_scene.h"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (argc < 2) {
    if (rank == 0) std::fprintf(stderr, "usage: mpi_smoke SCENE.yaml\n");
    MPI_Finalize();
    return 2;
  }
  const disco::Settings settings = disco::Settings::load(disco::default_settings_path());
  const int kOwn = 3;
  // Per solve: steps, solved (0/1), T_f, lower bound.
  std::vector<double> mine;
  for (int k = 0; k <= kOwn; ++k) {
    const int steps = k < kOwn ? 10 + rank + 2 * k : 12;  // the last one is shared
    const disco::Scene scene = disco::load_scene(argv[1], {"steps=" + std::to_string(steps)});
    const disco::SceneSolve run = disco::solve_scene(scene, settings);
    mine.push_back(steps);
    mine.push_back(run.solved() ? 1.0 : 0.0);
    mine.push_back(run.T_f());
    mine.push_back(run.problem->lower_bound().value_or(NAN));
  }
  const int per_rank = static_cast<int>(mine.size());
  std::vector<double> all(static_cast<size_t>(per_rank) * size);
  MPI_Allgather(mine.data(), per_rank, MPI_DOUBLE, all.data(), per_rank, MPI_DOUBLE,
                MPI_COMM_WORLD);

  int failures = 0;
  for (int r = 0; r < size; ++r) {
    for (int k = 0; k <= kOwn; ++k) {
      const double* v = &all[static_cast<size_t>(r) * per_rank + 4 * k];
      const double gap = (v[2] - v[3]) / v[3];
      const bool ok = v[1] == 1.0 && std::abs(gap) < 0.02;
      if (rank == 0)
        std::printf("rank %d solve %d: N_t %.0f solved %.0f T_f %.6f bound %.6f gap %+.3f %% %s\n",
                    r, k, v[0], v[1], v[2], v[3], 100 * gap, ok ? "ok" : "FAIL");
      failures += ok ? 0 : 1;
    }
    const double shared0 = all[4 * kOwn + 2];
    const double shared_r = all[static_cast<size_t>(r) * per_rank + 4 * kOwn + 2];
    if (shared0 != shared_r) {
      if (rank == 0) std::printf("shared instance differs: rank 0 %.17g, rank %d %.17g\n", shared0, r, shared_r);
      ++failures;
    }
  }
  if (rank == 0) std::printf("%d passed, %d failed\n", size * (kOwn + 1) - failures, failures);
  MPI_Finalize();
  return failures == 0 ? 0 : 1;
}
