"""A client of a running ``spinfold serve`` (the HTTP API of README, "HTTP API"), standard library
only: sessions (create, patch, advance, play, pause, state, trajectory), frames, and the live UI of
a session embedded in a notebook. An error answer (problem+json) raises ServerError with its fields.
"""

from __future__ import annotations

import json
import urllib.error
import urllib.parse
import urllib.request
from typing import Any, Mapping

__all__ = ["Client", "Session", "ServerError"]


class ServerError(Exception):
    """An answer of 400 and above: the problem+json fields (RFC 9457) as attributes."""

    def __init__(self, status: int, problem: Mapping[str, Any]):
        self.status = status
        self.title: str = str(problem.get("title", ""))
        self.detail: str = str(problem.get("detail", ""))
        self.type: str = str(problem.get("type", "about:blank"))
        self.errors: list[dict[str, Any]] = list(problem.get("errors", []))
        """Each wrong field: {"field", "value", "reason"}."""
        self.problem = dict(problem)
        super().__init__(f"{status} {self.title}: {self.detail}")


class Client:
    """The server at `url` (e.g. ``http://127.0.0.1:8080``)."""

    def __init__(self, url: str, timeout: float = 30.0):
        if not isinstance(url, str) or not url.startswith(("http://", "https://")):
            raise ValueError(f"url: must start with http:// or https:// (got {url!r})")
        self.url = url.rstrip("/")
        self.timeout = timeout

    def _request(self, method: str, path: str, body: Any = None, content_type: str = "application/json",
                 raw: bool = False) -> Any:
        data = None if body is None else json.dumps(body, allow_nan=False).encode()
        request = urllib.request.Request(self.url + path, data=data, method=method)
        if data is not None:
            request.add_header("Content-Type", content_type)
        try:
            with urllib.request.urlopen(request, timeout=self.timeout) as answer:
                payload = answer.read()
                if raw:
                    return payload, dict(answer.headers)
                return json.loads(payload) if payload else None
        except urllib.error.HTTPError as error:
            payload = error.read()
            try:
                problem = json.loads(payload)
            except ValueError:
                problem = {"title": error.reason, "detail": payload.decode(errors="replace")}
            raise ServerError(error.code, problem if isinstance(problem, dict) else {"detail": str(problem)}) from None

    def health(self) -> dict[str, Any]:
        """``GET /api/v1/health``: status, version, commit, sessions, streams."""
        return self._request("GET", "/api/v1/health")

    def presets(self) -> list[dict[str, Any]]:
        """The server's preset scenes."""
        return self._request("GET", "/api/v1/scenes")

    def create(self, scene: Any = None) -> "Session":
        """A new session on a scene (a dict), a preset name, or the default preset (None)."""
        if scene is None:
            body: Any = {"preset": "spinning_rigid_sphere"}
        elif isinstance(scene, str):
            body = {"preset": scene}
        elif isinstance(scene, Mapping):
            body = dict(scene)
        else:
            raise TypeError(f"scene: must be a preset name or a dict (got {type(scene).__name__})")
        answer = self._request("POST", "/api/v1/sessions", body)
        return Session(self, answer["id"], answer)

    def session(self, session_id: str) -> "Session":
        """An existing session by its id."""
        return Session(self, session_id, self._request("GET", f"/api/v1/sessions/{_quote(session_id)}"))


def _quote(text: str) -> str:
    return urllib.parse.quote(text, safe="")


class Session:
    """One session of the server: the last answer is in ``data`` (id, state, scene, timeline …)."""

    def __init__(self, client: Client, session_id: str, data: Mapping[str, Any]):
        self.client = client
        self.id = session_id
        self.data = dict(data)

    @property
    def _path(self) -> str:
        return f"/api/v1/sessions/{_quote(self.id)}"

    def _update(self, answer: Any) -> dict[str, Any]:
        if isinstance(answer, dict) and "id" in answer:
            self.data = answer
        return answer

    @property
    def state(self) -> dict[str, Any]:
        """The current sample (GET)."""
        return self._update(self.client._request("GET", self._path))["state"]

    def patch(self, changes: Mapping[str, Any]) -> dict[str, Any]:
        """A JSON merge patch of the scene (the run continues, or restarts where it must)."""
        return self._update(
            self.client._request("PATCH", self._path, dict(changes), content_type="application/merge-patch+json"))

    def advance(self, until: float | None = None, steps: int | None = None) -> dict[str, Any]:
        """Advances to time `until`, or by `steps` steps."""
        if (until is None) == (steps is None):
            raise ValueError("advance: give exactly one of until and steps")
        body = {"until": float(until)} if until is not None else {"steps": int(steps)}
        return self._update(self.client._request("POST", self._path + "/advance", body))

    def play(self, rate: float = 1.0) -> dict[str, Any]:
        """Advances in real time on the server, `rate` simulated time per second."""
        return self._update(self.client._request("POST", self._path + "/play", {"rate": float(rate)}))

    def pause(self) -> dict[str, Any]:
        return self._update(self.client._request("POST", self._path + "/pause", {}))

    def reset(self) -> dict[str, Any]:
        return self._update(self.client._request("POST", self._path + "/reset", {}))

    def delete(self) -> None:
        self.client._request("DELETE", self._path)

    def trajectory(self, every: float = 0.5, fields: str | None = None) -> list[dict[str, Any]]:
        """The run's samples at 0, every, … up to the session's time (replayed on the server)."""
        query = {"format": "json", "every": repr(float(every))}
        if fields:
            query["fields"] = fields
        return self.client._request("GET", self._path + "/trajectory?" + urllib.parse.urlencode(query))

    def frame(self, width: int = 640, height: int = 480, **params: Any):
        """The session's frame now as a spinfold.Frame (the server's PNG, decoded)."""
        from . import Frame  # the package imports this module first
        query = urllib.parse.urlencode({"width": width, "height": height, **params})
        png, _ = self.client._request("GET", self._path + "/frame.png?" + query, raw=True)
        return Frame.from_png(png)

    def ui_url(self, embed: bool = True) -> str:
        """The browser UI showing this session (embedded: without the page's chrome)."""
        query = urllib.parse.urlencode({"session": self.id, **({"embed": 1} if embed else {})})
        return f"{self.client.url}/?{query}"

    def show(self, width: int = 900, height: int = 600):
        """Embeds the live UI of this session in a notebook (an IFrame of ``?embed=1``)."""
        from IPython.display import IFrame  # only in a notebook
        return IFrame(self.ui_url(embed=True), width=width, height=height)

    def __repr__(self) -> str:
        t = self.data.get("state", {}).get("t")
        return f"<spinfold.Session {self.id} t = {t}>"
