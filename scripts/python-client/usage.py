"""A realistic use of the Python client generated from openapi/openapi.json.

scripts/python-client-check type-checks this file with `mypy --strict` and runs it against a
live server: it builds requests with and without optional fields, narrows a solution by its
`method` and a candidate by `applicable`, and calls every /v1 operation once.
"""

from __future__ import annotations

import sys
from typing import TypeVar

from knotshape_client import AuthenticatedClient, Client
from knotshape_client.api.curves import (
    approximate,
    bezier,
    closest_point,
    elevate_degree,
    envelope,
    evaluate,
    export,
    import_,
    insert_knots,
    interpolate,
    length,
    remove_knots,
    split,
)
from knotshape_client.api.shape import membership, regions, solve
from knotshape_client.models import (
    ApplicableMembershipCandidate,
    ApproximateRequest,
    ApproximateResponse,
    BezierRequest,
    BezierResponse,
    ClosestPointRequest,
    ClosestPointResponse,
    ConstraintBody,
    ControlPointSolutionBody,
    CurveBody,
    ElevateDegreeResponse,
    ElevateDegreeRequest,
    EnvelopeRequest,
    EnvelopeResponse,
    EvaluateRequest,
    EvaluateResponse,
    ExportRequest,
    FileFormat,
    ImportRequest,
    ImportResponse,
    InapplicableMembershipCandidate,
    InsertKnotsRequest,
    InsertKnotsResponse,
    InterpolateRequest,
    InterpolateResponse,
    KnotSolutionBody,
    LengthRequest,
    LengthResponse,
    MembershipResponse,
    Method,
    Problem,
    RegionsRequest,
    RegionsResponse,
    RemoveKnotsRequest,
    RemoveKnotsResponse,
    ShapeRequest,
    SolveResponse,
    SplitRequest,
    SplitResponse,
    WeightSolutionBody,
)
from knotshape_client.types import Unset


def sample_curve() -> CurveBody:
    return CurveBody(
        degree=3,
        control_points=[[0, 0], [1, 3], [3, 4], [5, 3.5], [6, 1], [8, 0], [9, 2], [10, 4]],
        knots=[0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1],
    )


T = TypeVar("T")


def expect(answer: T | Problem | None, kind: type[T]) -> T:
    """The answer when it is of `kind`; a problem (or nothing) ends the run with its detail."""
    if isinstance(answer, kind):
        return answer
    if isinstance(answer, Problem):
        sys.exit(f"problem {answer.status}: {answer.title}: {answer.detail}")
    sys.exit(f"unexpected answer {answer!r}")


def describe_solve(answer: SolveResponse) -> list[str]:
    lines = []
    for solution in answer.solutions:
        if isinstance(solution, KnotSolutionBody):
            lines.append(f"knots {solution.region} {solution.side}: {solution.changed_knots}")
        elif isinstance(solution, ControlPointSolutionBody):
            lines.append(f"control points {solution.changed_control_points}")
        elif isinstance(solution, WeightSolutionBody):
            lines.append(f"weights {solution.poles}: {solution.weights[solution.poles[0]]:.3f}")
        lines.append(f"  deviation {solution.max_deviation:.4f}, residual {solution.residual:.1e}")
    for candidate in answer.candidates:
        if isinstance(candidate, ApplicableMembershipCandidate):
            if not isinstance(candidate.frame, Unset):
                lines.append(f"{candidate.side} frame x = {candidate.frame.x:.3f}")
        elif isinstance(candidate, InapplicableMembershipCandidate):
            lines.append(f"{candidate.side} does not apply: {candidate.reason}")
    for exclusion in answer.excluded:
        lines.append(f"excluded {exclusion.count} of {exclusion.method}: {exclusion.reason}")
    return lines


def main(base_url: str, token: str | None) -> None:
    """Calls every /v1 operation: with the key when one is given, else with a plain client
    (a service without a key; the API key is optional in the document)."""
    client: AuthenticatedClient | Client
    if token is None:
        client = Client(base_url=base_url, raise_on_unexpected_status=True)
    else:
        client = AuthenticatedClient(base_url=base_url, token=token, raise_on_unexpected_status=True)
    curve = sample_curve()

    points = expect(
        evaluate.sync(client=client, body=EvaluateRequest(curve=curve, parameters=[0, 0.5, 1], derivatives=1)),
        EvaluateResponse,
    )
    assert points.points[-1] == [10, 4], points.points
    closest = expect(
        closest_point.sync(client=client, body=ClosestPointRequest(curve=curve, points=[[4.6, 3.4]])),
        ClosestPointResponse,
    )
    t = closest.results[0].parameter

    edit = ShapeRequest(
        curve=curve,
        parameter=t,
        target=[4.8, 3.2],
        methods=[Method.KNOTS, Method.CONTROL_POINTS, Method.WEIGHTS],
        nearest=True,
        constraints=[ConstraintBody(parameter=0.0, order=1), ConstraintBody(parameter=1.0, order=0)],
    )
    solved = expect(solve.sync(client=client, body=edit), SolveResponse)
    assert solved.reachable and solved.solutions, solved
    print("\n".join(describe_solve(solved)))
    reach = expect(membership.sync(client=client, body=edit), MembershipResponse)
    assert reach.reachable
    drawn = expect(
        regions.sync(client=client, body=RegionsRequest(curve=curve, parameter=t, methods=[Method.KNOTS, Method.WEIGHTS])),
        RegionsResponse,
    )
    assert drawn.candidates and drawn.weight_regions

    moved_knot = expect(
        envelope.sync(client=client, body=EnvelopeRequest(curve=curve, knot_index=5)), EnvelopeResponse
    )
    assert moved_knot.multiplicity == 1
    inserted = expect(
        insert_knots.sync(client=client, body=InsertKnotsRequest(curve=curve, knots=[0.5])), InsertKnotsResponse
    )
    assert len(inserted.curve.control_points) == 9
    pieces = expect(bezier.sync(client=client, body=BezierRequest(curve=curve)), BezierResponse)
    assert isinstance(pieces.svg_path, str) and not isinstance(pieces.svg_path, Unset)

    through = expect(
        interpolate.sync(client=client, body=InterpolateRequest(points=[[0, 0], [1, 2], [3, 2], [4, 0], [6, 1]])),
        InterpolateResponse,
    )
    fitted = expect(
        approximate.sync(
            client=client,
            body=ApproximateRequest(points=[[x / 10, (x / 10) ** 2] for x in range(40)], tolerance=1e-3),
        ),
        ApproximateResponse,
    )
    assert fitted.max_error <= 1e-3
    elevated = expect(
        elevate_degree.sync(client=client, body=ElevateDegreeRequest(curve=through.curve, degree=4)),
        ElevateDegreeResponse,
    )
    cleaned = expect(
        remove_knots.sync(client=client, body=RemoveKnotsRequest(curve=elevated.curve, tolerance=0.0)),
        RemoveKnotsResponse,
    )
    pieces_of = expect(split.sync(client=client, body=SplitRequest(curve=curve, parameters=[0.5])), SplitResponse)
    assert len(pieces_of.curves) == 2
    measured = expect(length.sync(client=client, body=LengthRequest(curve=curve, at_lengths=[1.0])), LengthResponse)
    print(f"length {measured.length:.6f}, removed {len(cleaned.removed)} knots")

    step_text = expect(
        export.sync(client=client, body=ExportRequest(format_=FileFormat.STEP, curves=[curve])), str
    )
    read_back = expect(
        import_.sync(client=client, body=ImportRequest(format_=FileFormat.STEP, data=step_text)), ImportResponse
    )
    assert len(read_back.curves) == 1 and read_back.curves[0].source.startswith("#")
    print("python client: every /v1 operation answered")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else None)
