// The WebSocket to the dashboard server: frames by kind to listeners, requests answered by id, reconnects.
export class Connection {
  constructor(url) {
    this.url = url;
    this.listeners = {};
    this.pending = new Map();
    this.nextId = 1;
    this.open = false;
    this.connect();
  }

  on(kind, fn) {
    (this.listeners[kind] ||= []).push(fn);
  }

  emit(kind, frame) {
    for (const fn of this.listeners[kind] || []) fn(frame);
  }

  connect() {
    const ws = new WebSocket(this.url);
    this.ws = ws;
    ws.onopen = () => {
      this.open = true;
      this.emit('open', {});
    };
    ws.onclose = () => {
      this.open = false;
      for (const [, p] of this.pending) p.resolve({ ok: false, message: 'the dashboard server went away' });
      this.pending.clear();
      this.emit('close', {});
      setTimeout(() => this.connect(), 1000);
    };
    ws.onmessage = (ev) => {
      let frame;
      try {
        frame = JSON.parse(ev.data);
      } catch {
        return;
      }
      if (frame.kind === 'reply' && this.pending.has(frame.id)) {
        this.pending.get(frame.id).resolve(frame);
        this.pending.delete(frame.id);
      }
      this.emit(frame.kind, frame);
    };
  }

  // Sends a request and resolves with the server's reply ({ok, message}).
  request(body) {
    const id = this.nextId++;
    return new Promise((resolve) => {
      if (!this.open) {
        resolve({ ok: false, message: 'not connected to the dashboard server' });
        return;
      }
      this.pending.set(id, { resolve });
      this.ws.send(JSON.stringify({ ...body, id }));
    });
  }

  // Sends without waiting for a reply (slider moves); errors still arrive as replies with id 0.
  send(body) {
    if (this.open) this.ws.send(JSON.stringify({ ...body, id: 0 }));
  }

  publish(channel, type, msg) {
    return this.request({ op: 'publish', channel, type, msg });
  }
}
