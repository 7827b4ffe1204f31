// An independent WebSocket client (the npm `ws` package, pinned by tests/foxglove/peer's lock
// file) for services/websocket's test.
//   node ws_client.js URL OPTIONS_JSON
// OPTIONS_JSON: {"protocols": ["..."] (offered subprotocols), "stall": false (after the
// handshake it stops reading its socket: the kernel's buffers, then the server's queue fill)}.
// The server drives it with text messages: "send:TEXT" is answered with TEXT, "send-size:N"
// with a text of N bytes, "report?" with a report line; any other message is counted.
// Prints JSON lines: {"event":"open","protocol"}, {"event":"refused","status","body"},
// {"event":"message","text"} (texts of at most 256 bytes), {"event":"report","received",
// "bytes"} (messages and bytes counted before the report), {"event":"close","code"},
// {"event":"error","message"}. Exits 0 once the connection is closed.
"use strict";
const { WebSocket } = require("ws");

const url = process.argv[2];
const options = JSON.parse(process.argv[3] || "{}");

function print(value) {
  process.stdout.write(JSON.stringify(value) + "\n");
}

const ws = new WebSocket(url, options.protocols || []);
let received = 0;
let bytes = 0;

ws.on("open", () => {
  print({ event: "open", protocol: ws.protocol });
  if (options.stall) {
    ws._socket.pause();
    // A socket that does not read keeps no event loop alive: this timer does, until killed.
    setInterval(() => {}, 1 << 30);
  }
});
ws.on("unexpected-response", (_request, response) => {
  let body = "";
  response.on("data", (chunk) => (body += chunk));
  response.on("end", () => {
    print({ event: "refused", status: response.statusCode, body });
    process.exit(0);
  });
});
ws.on("message", (data, isBinary) => {
  const text = isBinary ? null : data.toString();
  if (text === "report?") {
    print({ event: "report", received, bytes });
    return;
  }
  received += 1;
  bytes += data.length;
  if (text !== null && text.startsWith("send:")) {
    ws.send(text.slice("send:".length));
  } else if (text !== null && text.startsWith("send-size:")) {
    ws.send("y".repeat(Number(text.slice("send-size:".length))));
  }
  if (data.length <= 256) print({ event: "message", binary: isBinary, text });
});
ws.on("close", (code) => {
  print({ event: "close", code });
  process.exit(0);
});
ws.on("error", (error) => print({ event: "error", message: String(error && error.message) }));
