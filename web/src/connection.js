// WebSocket client for `holey serve`: numbered requests answered by one
// `ok`/`error`, pushed `state`/`progress` messages and binary mesh frames.
// Reconnects with backoff; every pending request fails on a disconnect so
// that no button stays stuck waiting for an answer that cannot come.

export class RequestError extends Error {
  constructor(msg) {
    super(msg.message || 'request failed');
    this.reply = msg;
    this.cancelled = !!msg.cancelled;
  }
}

export class Connection {
  constructor(url, handlers) {
    this.url = url;
    this.h = handlers; // { open, close, state, frame(ArrayBuffer), progress, notice }
    this.nextId = 1;
    this.pending = new Map();
    this.ws = null;
    this.retry = 0;
    this.everOpened = false;
    this.connect();
  }

  get open() {
    return this.ws && this.ws.readyState === WebSocket.OPEN;
  }

  connect() {
    const ws = new WebSocket(this.url);
    ws.binaryType = 'arraybuffer';
    this.ws = ws;
    ws.onopen = () => {
      this.retry = 0;
      this.everOpened = true;
      this.h.open?.();
    };
    ws.onmessage = (ev) => {
      if (typeof ev.data !== 'string') {
        this.h.frame?.(ev.data);
        return;
      }
      let msg;
      try {
        msg = JSON.parse(ev.data);
      } catch {
        this.h.notice?.('The server sent a message that is not JSON.');
        return;
      }
      this.dispatch(msg);
    };
    ws.onclose = () => {
      if (this.ws !== ws) return;
      for (const p of this.pending.values()) p.reject(new RequestError({ message: 'connection to the server lost' }));
      this.pending.clear();
      // Back off up to 5 s so a restarted server is picked up quickly.
      const delay = Math.min(5000, 300 * 2 ** this.retry++);
      this.h.close?.(delay);
      setTimeout(() => this.connect(), delay);
    };
    ws.onerror = () => {}; // onclose follows and handles it
  }

  dispatch(msg) {
    switch (msg.type) {
      case 'state':
        this.h.state?.(msg);
        break;
      case 'progress':
        this.h.progress?.(msg);
        break;
      case 'ok':
      case 'error': {
        const p = this.pending.get(msg.id);
        if (!p) break;
        this.pending.delete(msg.id);
        if (msg.type === 'ok') p.resolve(msg);
        else p.reject(new RequestError(msg));
        break;
      }
      default:
        break; // unknown message types are ignored for forward compatibility
    }
  }

  /** Send a request; resolves with the `ok` message, rejects with RequestError. */
  request(op, fields = {}) {
    if (!this.open) return Promise.reject(new RequestError({ message: 'not connected to the server' }));
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, op });
      this.ws.send(JSON.stringify({ id, op, ...fields }));
    });
  }
}
