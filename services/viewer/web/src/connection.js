// The live WebSocket: messages from the viewer (hello, frame, depth) and clock commands to it.
// Reconnects after a loss, so that a viewer restarted on the same port is picked up again.

export class Connection {
  constructor(onMessage, onStatus) {
    this.onMessage = onMessage;
    this.onStatus = onStatus;
    this.socket = null;
    this.open();
  }

  open() {
    const url = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`;
    const socket = new WebSocket(url);
    this.socket = socket;
    socket.onopen = () => this.onStatus('live');
    socket.onmessage = (event) => {
      let message;
      try {
        message = JSON.parse(event.data);
      } catch (e) {
        console.warn('viewer: a message that is not JSON', e);
        return;
      }
      this.onMessage(message);
    };
    socket.onclose = () => {
      // After the run the viewer leaves: nothing to reconnect to.
      this.onStatus(this.ended ? 'ended' : 'disconnected');
      if (!this.ended) setTimeout(() => this.open(), 1000);
    };
    socket.onerror = () => {};  // onclose follows and reconnects
  }

  /** Sends a clock command ({cmd: 'pause'} ...); false if not connected. */
  send(command) {
    if (!this.socket || this.socket.readyState !== WebSocket.OPEN) return false;
    this.socket.send(JSON.stringify(command));
    return true;
  }
}
