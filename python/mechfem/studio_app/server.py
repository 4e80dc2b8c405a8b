"""The studio's web application: Starlette (routing, websocket) served by uvicorn, on 127.0.0.1 only.

Every request and the websocket must carry the random token of the address printed at start (``?token=...``);
the Host header must name the loopback address the server listens on, so that a web page elsewhere can neither read
the page (DNS rebinding) nor drive the websocket. The page is one HTML document with its scripts inlined (as the
report is); everything else goes over the websocket as JSON messages, each answered by the new view (after an edit:
only what differs from the view the page has, :mod:`.delta`) or by the words saying why an edit was refused.

The server reads decks only where the user points it (the path given on the command line, a file the browser sends,
the repository's examples) and writes only the files of a save, at the path typed into the page.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import hmac
import json
import secrets
import socket
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import orjson
import uvicorn
from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import HTMLResponse, PlainTextResponse, Response
from starlette.routing import Route, WebSocketRoute
from starlette.types import ASGIApp, Receive, Scope, Send
from starlette.websockets import WebSocket, WebSocketDisconnect

from mechfem.studio_app.actions import Actions
from mechfem.studio_app.delta import changes
from mechfem.studio_app.page import render_page
from mechfem.studio_app.session import Session

HOST = "127.0.0.1"


class TokenGate:
    """ASGI middleware: a request or websocket without the right ``token`` query parameter is refused (403)."""

    def __init__(self, app: ASGIApp, token: str) -> None:
        self.app = app
        self.token = token.encode()

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket"):
            query = scope.get("query_string", b"").decode("latin-1")
            given = next((p[6:] for p in query.split("&") if p.startswith("token=")), "")
            if not hmac.compare_digest(given.encode("latin-1"), self.token):
                if scope["type"] == "websocket":
                    await send({"type": "websocket.close", "code": 1008})
                    return
                response = PlainTextResponse("mechfem studio: this address needs the token it was started with", 403)
                await response(scope, receive, send)
                return
        await self.app(scope, receive, send)


def make_app(actions: Actions, token: str, port: int) -> Starlette:
    """The application for ``actions`` behind ``token``, answering to the loopback address on ``port`` only."""

    async def page(request: Request) -> Response:
        host = f"{HOST}:{port}"
        return HTMLResponse(render_page(host), headers={"Cache-Control": "no-store", "Referrer-Policy": "no-referrer"})

    async def live(ws: WebSocket) -> None:
        await ws.accept()
        loop = asyncio.get_running_loop()
        lock = asyncio.Lock()

        # The design the page has (as sent): an edit's answer carries only what differs from it.
        shown: list[dict[str, Any] | None] = [None]

        pushed: list[concurrent.futures.Future[None]] = []

        def push(message: dict[str, Any]) -> None:
            # Called from the worker thread of a long action (an optimisation's iterations, each sent whole).
            if "design" in message:
                shown[0] = message["design"]
            pushed.append(asyncio.run_coroutine_threadsafe(ws.send_text(dumps(message)), loop))

        def answer(message: dict[str, Any]) -> str:
            # Wall and CPU time of the answer (the CPU time of this thread: what the edit costs on an idle machine).
            started, cpu = time.perf_counter(), time.thread_time()
            text = dumps(only_changes(actions.handle(message, push), shown))
            wall, used = 1000 * (time.perf_counter() - started), 1000 * (time.thread_time() - cpu)
            # The reply is a JSON object: the two times go in before its closing brace, without a second dump.
            return f'{text[:-1]},"server_ms":{wall:.2f},"server_cpu_ms":{used:.2f}}}'

        await ws.send_text(dumps(only_changes(actions.hello(), shown)))
        try:
            while True:
                text = await ws.receive_text()
                async with lock:
                    reply = await asyncio.to_thread(answer, json.loads(text))
                    # The answer's changes are to the last design pushed: it goes after every push.
                    for sent in pushed:
                        await asyncio.wrap_future(sent)
                    pushed.clear()
                    await ws.send_text(reply)
        except WebSocketDisconnect:
            return

    hosts = [HOST, f"{HOST}:{port}", "localhost", f"localhost:{port}"]
    app = Starlette(
        routes=[Route("/", page), WebSocketRoute("/ws", live)],
        middleware=[Middleware(TrustedHostMiddleware, allowed_hosts=hosts), Middleware(TokenGate, token=token)],
    )
    return app


def only_changes(reply: dict[str, Any], shown: list[dict[str, Any] | None]) -> dict[str, Any]:
    """``reply`` with its design replaced by what differs from ``shown[0]`` (the design the page has; then set to
    the new one), unless it opens another design (sent whole)."""
    design = reply.get("design")
    if design is None:
        return reply
    before, shown[0] = shown[0], design
    if before is None or reply.get("opened") or reply.get("type") == "hello":
        return reply
    return {**{k: v for k, v in reply.items() if k != "design"}, "changes": changes(before, design)}


def dumps(message: dict[str, Any]) -> str:
    """``message`` as JSON text, as the page gets it."""
    # orjson: a design's answer (some 100 kB of numbers) in a tenth of json.dumps's time; numpy arrays as they are,
    # a number that is not finite as null.
    return orjson.dumps(message, default=_listed, option=orjson.OPT_SERIALIZE_NUMPY).decode()


def _listed(value: Any) -> Any:
    """What orjson does not write itself: a numpy array that is not C-contiguous (a column of a table)."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON serializable")


def free_socket(port: int = 0) -> socket.socket:
    """A listening TCP socket on 127.0.0.1 (``port`` 0: a free one the system picks)."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind((HOST, port))
    sock.listen(16)
    return sock


@dataclass
class Running:
    """A studio server running in a thread of this process (tests, notebooks): its ``url`` with the token."""

    url: str
    server: uvicorn.Server
    thread: threading.Thread
    actions: Actions
    closers: list[Callable[[], object]] = field(default_factory=list)

    def stop(self) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=10)


def studio_url(port: int, token: str) -> str:
    return f"http://{HOST}:{port}/?token={token}"


def prepare(session: Session | None, port: int = 0, **options: Any) -> tuple[uvicorn.Server, socket.socket, str]:
    """The server (not started), its listening socket and its address with a new token."""
    token = secrets.token_urlsafe(24)
    sock = free_socket(port)
    port = sock.getsockname()[1]
    actions = Actions(session, **options)
    # No per-message compression: on loopback, deflating every view costs more time than it saves.
    config = uvicorn.Config(
        make_app(actions, token, port),
        log_level="warning",
        ws="websockets-sansio",
        ws_per_message_deflate=False,
        lifespan="off",
    )
    server = uvicorn.Server(config)
    server.actions = actions  # type: ignore[attr-defined]
    return server, sock, studio_url(port, token)


def serve_in_thread(session: Session | None, port: int = 0, **options: Any) -> Running:
    """Starts a studio server on a thread of its own; returns once it accepts connections."""
    server, sock, url = prepare(session, port, **options)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True, name="mechfem-studio")
    thread.start()
    deadline = time.monotonic() + 10
    while not server.started and time.monotonic() < deadline:
        time.sleep(0.01)
    return Running(url, server, thread, server.actions)  # type: ignore[attr-defined]


def serve(
    session: Session | None, port: int = 0, on_start: Callable[[str], object] | None = None, **options: Any
) -> None:
    """Serves until interrupted (Ctrl-C); ``on_start(url)`` is called once the server listens."""
    server, sock, url = prepare(session, port, **options)
    if on_start is not None:
        on_start(url)
    server.run(sockets=[sock])


__all__ = ["HOST", "Running", "TokenGate", "dumps", "make_app", "only_changes", "serve", "serve_in_thread"]
