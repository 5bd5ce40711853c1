"""Which figures a run gets: the Plot record (output name, input file, draw
function, whether it applies), the per-problem plots keyed by
summary["problem"], the generic ones keyed by their input file, and
plots_for."""

from dataclasses import dataclass
from functools import partial
from typing import Callable, Dict, List, Optional

from .cells import plot_slice_fields
from .curves import plot_beam_tip, plot_pile_wall_stress, plot_sod_profiles, plot_wilkins_profiles
from .fields import maps_apply, plot_density_snapshots, plot_field_maps, plot_fields_vs_lagrange
from .history import plot_history
from .mesh import not_remap, plot_mesh, plot_snapshot_mesh, snapshot_mesh_applies
from .radial import plot_radial
from .readers import Run
from .shapes import plot_rod, plot_shell, plot_taylor, plot_taylor_outline


def always(run: Run) -> bool:
    return True


@dataclass(frozen=True)
class Plot:
    """One output figure: its file name, the input it needs, how to draw it,
    and whether it applies to a run (checked before its input is read)."""
    output: str
    source: str
    draw: Callable[[Run, str], Optional[str]]
    applies: Callable[[Run], bool] = always


# Plots that only make sense for one problem, keyed by summary["problem"].
PROBLEM_PLOTS: Dict[str, List[Plot]] = {
    "sod": [Plot("sod_profiles.png", "sod_profile.csv", plot_sod_profiles)],
    "wilkins": [Plot("wilkins_profiles.png", "wilkins_profile.csv", plot_wilkins_profiles)],
    "pile": [Plot("pile_wall_stress.png", "pile_wall_stress.csv", plot_pile_wall_stress)],
    "taylor": [Plot("taylor.png", "taylor_mesh_z0.csv", plot_taylor),
               Plot("taylor_outline.png", "fields.xmf", plot_taylor_outline),
               Plot("mesh.png", "taylor_mesh_z0.csv",
                    partial(plot_mesh, source="taylor_mesh_z0.csv"), not_remap)],
    "shell": [Plot("shell.png", "shell_mesh_z0.csv", plot_shell),
              Plot("mesh.png", "shell_mesh_z0.csv",
                   partial(plot_mesh, source="shell_mesh_z0.csv"), not_remap)],
    "beam": [Plot("beam_tip.png", "beam_tip.csv", plot_beam_tip)],
    "rod": [Plot("rod.png", "rod_plane_z0.csv", plot_rod),
            Plot("mesh.png", "rod_plane_z0.csv",
                 partial(plot_mesh, source="rod_plane_z0.csv"), not_remap)],
}

# Plots drawn for any problem, as long as the run wrote their input: radial
# output is written by every radially symmetric problem (sedov, noh, ...) and
# the slice by every 3D one, so keying them on the file keeps new problems
# plotted without touching this registry.
GENERIC_PLOTS: List[Plot] = [
    Plot("radial_density.png", "radial.csv", partial(plot_radial, field="rho")),
    Plot("radial_pressure.png", "radial.csv", partial(plot_radial, field="p")),
    Plot("slice_fields.png", "slice_z.csv", plot_slice_fields),
    Plot("mesh.png", "fields.xmf", plot_snapshot_mesh, snapshot_mesh_applies),
    Plot("mesh.png", "slice_z.csv", partial(plot_mesh, source="slice_z.csv"), not_remap),
    Plot("fields_map.png", "fields.xmf", plot_field_maps, maps_apply),
    Plot("fields_vs_lagrange.png", "fields.xmf", plot_fields_vs_lagrange, maps_apply),
    Plot("density_snapshots.png", "fields.xmf", plot_density_snapshots, maps_apply),
    Plot("history.png", "history.csv", plot_history),
]


def plots_for(run: Run) -> List[Plot]:
    """The candidate plots for this run: problem-specific first, then generic."""
    return PROBLEM_PLOTS.get(run.problem, []) + GENERIC_PLOTS
