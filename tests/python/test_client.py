"""spinfold.Client against a real `spinfold serve` started for the tests."""

import numpy as np
import pytest

import spinfold


def test_sessions_through_the_api(server):
    client = spinfold.Client(server)
    health = client.health()
    assert health["status"] == "ok" and health["commit"]
    session = client.create("spinning_rigid_sphere")
    try:
        assert session.state["t"] == 0.0
        session.advance(until=1.5)
        assert session.state["t"] == 1.5
        session.patch({"body": {"mass": 2.0}})
        assert session.data["current"]["body"]["mass"] == 2.0
        session.advance(steps=10)
        rows = session.trajectory(every=0.5, fields="t,r")
        assert [row["t"] for row in rows[:4]] == [0.0, 0.5, 1.0, 1.5]
        assert set(rows[0]) == {"t", "r"}
        # The server's numbers are the engine's: its first rows are those of a local run.
        local = spinfold.simulate("spinning_rigid_sphere", t_end=1.5, every=0.5)
        assert [row["r"] for row in rows[:4]] == list(local["r"])
        frame = session.frame(width=160, height=120)
        assert frame.pixels.shape == (120, 160, 4)
        assert frame.pixels[:, :, :3].std() > 5  # a picture, not a blank
        assert "Source" in dict(frame.texts)
        session.play(rate=2.0)
        session.pause()
        session.reset()
        assert session.state["t"] == 0.0
        assert "session=" + session.id in session.ui_url() and "embed=1" in session.ui_url()
        iframe = session.show()
        assert session.id in iframe.src
    finally:
        session.delete()


def test_errors_carry_the_problem_fields(server):
    client = spinfold.Client(server)
    with pytest.raises(spinfold.ServerError) as caught:
        client.create({"initial": {"r": -1}})
    error = caught.value
    assert error.status == 422
    assert any(e.get("field") == "initial.r" for e in error.errors), error.problem
    session = client.create(None)
    try:
        before = session.state
        with pytest.raises(spinfold.ServerError) as caught:
            session.patch({"body": {"mass": "heavy"}})
        assert caught.value.status == 422 and caught.value.errors
        assert session.state == before  # nothing changed
    finally:
        session.delete()
    with pytest.raises(spinfold.ServerError) as caught:
        client.session("no-such-session")
    assert caught.value.status == 404
    with pytest.raises(ValueError):
        spinfold.Client("localhost:8080")
    with pytest.raises(ValueError):
        client.create(None).advance()
