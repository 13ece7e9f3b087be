// The climbsim viewer page: a live run over a WebSocket, or the replay of a finished run.
// window.climbsimViewer exposes what the browser tests read (and a user may, in the console).
import { drawLegend, scales } from './colors.js';
import { Connection } from './connection.js';
import { frameClock } from './frame_clock.js';
import { showDepth, showReadouts, showReplayRate, showRun, showSealingPicture } from './panels.js';
import { Plots } from './plots.js';
import { ReplayClock, samplesFromTrace } from './replay.js';
import { GAP_MAX_M, Scene3D, SUCTION_MAX_PA } from './scene3d.js';

const $ = (id) => document.getElementById(id);

const viewer = {
  mode: 'connecting',
  run: null,          // the latest run info (live)
  hello: null,
  frames: 0,          // frame messages received (live)
  states: 0,          // states received in them (live; plotted one point each)
  depths: 0,          // depth images received (live)
  scene: null,
  plots: null,
  replay: null,
  /** The latest plotted sample: {t, F, step} (tests compare it with trace.csv). */
  lastPlotted() {
    const s = viewer.plots?.last;
    return s ? { t: s.t, F: s.F, step: s.step, pfx: s.pfx, pfy: s.pfy } : null;
  },
  /** Replay: show the run at time t [s]. */
  seek(t) {
    viewer.replay?.seek(t);
    $('replay-slider').value = String(t);
  },
};
window.climbsimViewer = viewer;

function setupLegends(hello) {
  drawLegend($('legend-pressure'), scales.suction);
  drawLegend($('legend-gap'), scales.gap);
  drawLegend($('legend-height'), scales.height);
  $('legend-p-max').textContent = (SUCTION_MAX_PA / 1000).toFixed(0);
  $('legend-gap-max').textContent = (GAP_MAX_M * 1000).toFixed(0);
}

function setupViewButtons(scene) {
  const follow = $('btn-follow');
  follow.onclick = () => {
    scene.follow = !scene.follow;
    follow.classList.toggle('on', scene.follow);
    if (scene.follow) scene.setView('follow');
  };
  $('btn-behind').onclick = () => scene.setView('behind');
  $('btn-top').onclick = () => scene.setView('top');
  $('relief').onchange = () => scene.setRelief(Math.max(1, Number($('relief').value) || 1));
  $('plot-window').onchange = () => viewer.plots.setWindow(Number($('plot-window').value));
}

function start(hello) {
  viewer.hello = hello;
  const robot = hello?.robot;
  viewer.scene = new Scene3D($('view3d'));
  viewer.plots = new Plots($('plots'), robot ? robot.wheels.length : 3, robot ? robot.chambers.length : 7,
    robot ? robot.has_reservoir !== false : true);
  if (robot) viewer.scene.setRobot(robot);
  if (hello?.scenario) {
    const { x_m, y_m } = hello.scenario.start;
    viewer.scene.update({ pose: { position: [x_m, y_m, 0], rpy: [0, 0, hello.scenario.start.yaw_deg * Math.PI / 180] } });
    viewer.scene.setView('top');
  }
  setupLegends(hello);
  setupViewButtons(viewer.scene);
}

// ---- live ----------------------------------------------------------------------------------

/** The page's sample of a live frame: t is when the values hold (end of the stamped step), as trace.csv's rows. */
function sampleOfFrame(frame, setpoint) {
  const dt = frame.run.dt_s || 0;
  // The set-point the controller in force published with the force (null: no controller has
  // one, e.g. controller none or fixed), else the scenario's.
  const published = frame.force && 'setpoint_n' in frame.force ? (frame.force.setpoint_n ?? NaN) : undefined;
  const s = { t: frame.force ? frame.force.t_s + dt : frame.run.t_s, setpoint: published ?? setpoint };
  if (frame.force) Object.assign(s, { step: frame.force.step, F: frame.force.downforce_n, pfx: frame.force.pf_x_m, pfy: frame.force.pf_y_m });
  if (frame.chambers) Object.assign(s, { pressures: frame.chambers.pressure_pa, valves: frame.chambers.valve_opening });
  if (frame.wheels) Object.assign(s, { normal: frame.wheels.normal_n, slip: frame.wheels.slip_mps });
  if (frame.pose) s.pose = { position: frame.pose.position_m, quaternion: frame.pose.orientation_wxyz };
  if (frame.leak) s.leak = Object.fromEntries(Object.entries(frame.leak.segments).map(([k, v]) => [k, v.leak_area_m2]));
  return s;
}

function startLive(hello) {
  viewer.mode = 'live';
  start(hello);
  $('mode').textContent = 'live';
  const setpoint = hello?.scenario?.setpoint_n ?? NaN;
  const sealingSeen = {};
  // Messages are taken as they come (each sample in them goes into the plots and the track),
  // but the readouts, run panel, 3D state and depth are updated with the latest frame and depth
  // only, in the page's next frame (frame_clock.js, at most APPLY_FPS a second): a page that
  // renders slowly (software WebGL on a loaded machine) skips states instead of falling behind.
  const latest = { frame: null, depth: null };
  const APPLY_FPS = 5;  // readouts, run panel and 3D state: at most this often (each costs a layout)
  const apply = () => {
    const message = latest.frame;
    latest.frame = null;
    if (message) {
      viewer.run = message.run;
      viewer.lagMs = Date.now() - message.wall_unix_ms;
      const sample = sampleOfFrame(message, setpoint);
      showRun(message.run);
      showReadouts(sample);
      viewer.scene.update({ pose: sample.pose, pressures: sample.pressures, leak: sample.leak, normal: sample.normal, force: message.force ? sample : null });
      for (const [kind, version] of Object.entries(message.sealing_versions || {})) {
        if (sealingSeen[kind] !== version) {
          sealingSeen[kind] = version;
          showSealingPicture(kind, `live/sealing_${kind}.png?v=${version}`, message.run.t_s);
        }
      }
    }
    const depth = latest.depth;
    latest.depth = null;
    if (depth) {
      viewer.scene.setHeights(depth);
      showDepth(depth);
    }
  };
  const schedule = () => frameClock.request('panels', apply, { fps: APPLY_FPS, budget: 0.05 });
  const connection = new Connection((message) => {
    if (message.type === 'hello' && !viewer.hello?.robot && message.robot) {
      viewer.hello = message;
      viewer.scene.setRobot(message.robot);
    } else if (message.type === 'frame') {
      viewer.frames += 1;
      // The samples since the previous message (the viewer batches them), else the frame itself.
      for (const state of message.samples ?? [message]) {
        viewer.states += 1;
        const sample = sampleOfFrame({ ...state, run: message.run }, setpoint);
        if (state.force) viewer.plots.push(sample);
        if (sample.pose) viewer.scene.addTrackPoint(sample.pose.position);
      }
      if (['completed', 'stopped', 'failed'].includes(message.run.phase)) connection.ended = true;
      latest.frame = message;
      schedule();
    } else if (message.type === 'depth') {
      viewer.depths += 1;
      latest.depth = message;
      schedule();
    }
  }, (status) => {
    $('mode').textContent = status;
  });
  const send = (command) => connection.send(command);
  $('btn-pause').onclick = () => send({ cmd: 'pause' });
  $('btn-resume').onclick = () => send({ cmd: 'resume' });
  $('btn-step').onclick = () => send({ cmd: 'step', steps: Math.max(1, Math.round(Number($('step-count').value) || 1)) });
  $('btn-rtf').onclick = () => send({ cmd: 'rtf', value: Math.max(0, Number($('rtf-value').value) || 0) });
  $('btn-stop').onclick = () => send({ cmd: 'stop' });
  viewer.connection = connection;
}

// ---- replay --------------------------------------------------------------------------------

async function startReplay(hello) {
  viewer.mode = 'replay';
  start(hello);
  $('mode').textContent = 'replay';
  $('controls').hidden = true;
  $('replay-bar').hidden = false;
  const [trace, pictures] = await Promise.all([fetch('api/trace').then((r) => r.json()), fetch('api/pictures').then((r) => r.json())]);
  const robot = hello.robot;
  const samples = samplesFromTrace(trace, hello.scenario.setpoint_n, robot.segments.map((s) => s.name), robot.wheels.length,
    robot.chambers.length, robot.has_reservoir !== false);
  viewer.samples = samples;
  viewer.plots.setAll(samples);
  // Rows before the first RobotState hold nan (null here): no track point there.
  const track = samples.map((s) => s.pose.position);
  const firstPose = Math.max(0, track.findIndex((p) => p.every(Number.isFinite)));
  const slider = $('replay-slider');
  const end = samples.length ? samples[samples.length - 1].t : 0;
  slider.max = String(end);
  slider.step = String(hello.scenario.step_s);
  let shownTrack = -1;
  // The wall under the robot, if the live viewer kept depth grids in the run directory.
  // One request at a time; the time asked for meanwhile is fetched when it returns.
  const depth = { t: -1, wanted: 0, busy: false, none: false };
  viewer.depth = depth;  // what the page asked for last (snapshot.mjs waits for the time it shows)
  const fetchDepth = (time) => {
    depth.wanted = time;
    if (depth.busy || depth.none || Math.abs(time - depth.t) < 0.1) return;
    depth.busy = true;
    depth.t = time;
    fetch(`api/depth?t=${time}`).then((r) => r.json()).then((grid) => {
      depth.busy = false;
      if (!grid) { depth.none = true; return; }
      viewer.depths += 1;
      viewer.scene.setHeights(grid);
      showDepth(grid);
      fetchDepth(depth.wanted);
    }).catch(() => { depth.busy = false; });
  };
  const show = (index, time) => {
    const s = samples[index];
    if (!s) return;
    viewer.shown = s;
    viewer.scene.update({ pose: s.pose, pressures: s.pressures, leak: s.leak, normal: s.normal, force: s });
    // The track up to now, redrawn in steps of 1 % of the run (cheap while playing).
    const upto = Math.floor(index / Math.max(1, samples.length / 100));
    if (upto !== shownTrack) {
      shownTrack = upto;
      viewer.scene.setTrack(track.slice(firstPose, Math.max(firstPose, index + 1)));
    }
    showReadouts(s);
    // The header says the replay's speed (simulated s per wall s), not a real-time factor.
    const playing = viewer.replay?.playing ?? false;
    showRun({ t_s: s.t, rtf_measured: NaN, rtf_target: 0, phase: playing ? 'replaying' : 'paused', reason: '', roster: [] });
    showReplayRate(viewer.replay?.speed ?? Number($('replay-speed').value), playing);
    viewer.plots.setCursor(time);
    fetchDepth(time);
    if (document.activeElement !== slider) slider.value = String(time);
    for (const kind of ['gaps', 'edges']) {
      const shown = pictures.filter((p) => p.kind === kind && p.t_s <= time + 1e-9).pop();
      showSealingPicture(kind, shown ? `run/${shown.file}` : null, shown?.t_s);
    }
  };
  viewer.replay = new ReplayClock(samples, show);
  slider.oninput = () => viewer.replay.seek(Number(slider.value));
  $('btn-play').onclick = () => {
    if (viewer.replay.playing) viewer.replay.pause(); else viewer.replay.play();
    $('btn-play').textContent = viewer.replay.playing ? 'pause' : 'play';
    showReplayRate(viewer.replay.speed, viewer.replay.playing);
  };
  $('replay-speed').onchange = () => {
    viewer.replay.speed = Number($('replay-speed').value);
    showReplayRate(viewer.replay.speed, viewer.replay.playing);
  };
  // A finished run opens at its end: the whole run's plots and its last pictures (play starts over).
  viewer.replay.seek(end);
  viewer.ready = true;
  document.body.dataset.ready = 'replay';  // a DOM change: tests wait on mutations
}

async function main() {
  let hello = null;
  try {
    const response = await fetch('api/hello');
    if (response.ok) hello = await response.json();
  } catch (e) {
    console.warn('viewer: no /api/hello', e);
  }
  if (hello?.mode === 'replay') await startReplay(hello); else startLive(hello);
}

main();
