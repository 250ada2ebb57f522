"""Writes the Rerun blueprint (a .rbl file) of knotlab's README picture: the scene around the wound in 3D,
the instruments' forces and the wound gap over time, the grasp events and the verdict.

Usage: python scripts/rerun_blueprint.py OUT.rbl CENTRE_X,CENTRE_Y,CENTRE_Z
(needs the rerun-sdk Python package, the version knotlab's `rerun` crate pins: see scripts/rerun-picture)."""

import sys

import rerun as rr
import rerun.blueprint as rrb


def main() -> None:
    out, centre = sys.argv[1], [float(x) for x in sys.argv[2].split(",")]
    eye = [centre[0] + 0.10, centre[1] - 0.15, centre[2] + 0.10]
    view = rrb.Spatial3DView(
        name="trial around the wound",
        origin="/",
        contents=["+ /scene/**", "+ /instruments/**", "- /scene/robots/camera/**"],
        eye_controls=rrb.EyeControls3D(position=eye, look_target=centre, eye_up=[0.0, 0.0, 1.0]),
        background=[245, 245, 245],
    )
    plots = rrb.Vertical(
        rrb.TimeSeriesView(name="measured force (N)", origin="/plots/force_n"),
        rrb.TimeSeriesView(name="wound gap (m)", origin="/plots/wound_gap_m"),
        rrb.TextDocumentView(name="verdict", origin="/verdict"),
        rrb.TextLogView(name="events", origin="/events"),
        row_shares=[3, 2, 3, 2],
    )
    blueprint = rrb.Blueprint(
        rrb.Horizontal(view, plots, column_shares=[3, 2]),
        rrb.BlueprintPanel(state="collapsed"),
        rrb.SelectionPanel(state="collapsed"),
        rrb.TimePanel(state="collapsed", timeline="sim_time", play_state="following"),
    )
    blueprint.save("knotlab", out)


if __name__ == "__main__":
    main()
