// The 3D view (three.js): the wall frame W is the scene's frame (x across, y up, z out of the
// wall), so three.js's y-up default matches a vertical wall. The robot group carries the robot
// frame R: chambers coloured by suction, sealing strips coloured by their gap, wheels with
// normal-load arrows, the downforce arrow at P_F, and the height field of the wall under the
// robot from the latest depth image. The track is the robot's path in W.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { gapColor, heightColor, suctionColor } from './colors.js';
import { frameClock } from './frame_clock.js';
import { RenderScale } from './render_scale.js';

const MAX_TRACK = 50000;
const RENDER_FPS = 10;                // most 3D renders per second
// Share of one core the 3D renders may take: a render that costs more (software WebGL on a
// machine without a GPU: tens of ms) is repeated less often, so that the page watching a run
// does not take the CPU the run needs. With a GPU (about 1 ms) RENDER_FPS is the limit.
const RENDER_BUDGET = 0.05;
// Chambers and strips are drawn on a plate above the exaggerated wall relief (5 mm x 5), so
// the relief never hides them; from behind the wall they are seen through it.
const PLATE_Z_M = 0.03;
export const SUCTION_MAX_PA = 20000;  // colour scale of the chambers: 0 .. 20 kPa below ambient
export const GAP_MAX_M = 0.005;       // colour scale of the strips: 0 .. 5 mm (the sealing travel)
export const HEIGHT_RANGE_M = 0.005;  // colour scale of the wall: -5 .. +5 mm
const NEWTON_TO_M_WHEEL = 0.0005;     // wheel arrows: 0.5 mm per N
const NEWTON_TO_M_FORCE = 0.0001;     // downforce arrow: 0.1 mm per N

export class Scene3D {
  constructor(container) {
    this.container = container;
    // No multisampling: in software WebGL (a machine without a GPU) it multiplies the cost of a render.
    this.renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    this.resolution = new RenderScale(1);
    this.renderer.setPixelRatio(this.resolution.scale);
    this.renderer.setClearColor(0x1b2027);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 200);
    this.camera.position.set(0.8, -1.2, 2.2);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.requestRender());
    this.follow = true;
    this.relief = 5;
    this.robotPosition = new THREE.Vector3();

    this.scene.add(new THREE.AmbientLight(0xffffff, 1.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(1, 2, 3);
    this.scene.add(sun);
    const back = new THREE.DirectionalLight(0xffffff, 0.8);
    back.position.set(-1, -1, -3);
    this.scene.add(back);

    this.wall = new THREE.Group();
    this.scene.add(this.wall);
    const wallPlane = new THREE.Mesh(new THREE.PlaneGeometry(40, 40),
      new THREE.MeshLambertMaterial({ color: 0x6d6a64, side: THREE.FrontSide }));
    wallPlane.position.z = -0.002;
    this.wall.add(wallPlane);
    const grid = new THREE.GridHelper(40, 80, 0x8a857c, 0x7b776f);
    grid.rotation.x = Math.PI / 2;
    grid.position.z = -0.001;
    this.wall.add(grid);

    this.robot = new THREE.Group();
    this.scene.add(this.robot);
    this.heightMesh = null;

    const trackGeometry = new THREE.BufferGeometry();
    this.trackPositions = new Float32Array(MAX_TRACK * 3);
    trackGeometry.setAttribute('position', new THREE.BufferAttribute(this.trackPositions, 3));
    trackGeometry.setDrawRange(0, 0);
    this.track = new THREE.Line(trackGeometry, new THREE.LineBasicMaterial({ color: 0x4fd8ff }));
    // Never culled: its bounding sphere would have to be recomputed over every point as it grows.
    this.track.frustumCulled = false;
    this.trackCount = 0;
    this.scene.add(this.track);

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h);
    this.drawn = null;  // a resized canvas is cleared until the next render
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /** Renders in the page's next frame (frame_clock.js), at most RENDER_FPS times a second
   *  and within RENDER_BUDGET (WebGL in software on a loaded machine is the page's largest cost). */
  requestRender() {
    frameClock.request('3d', () => this.renderNow(), { fps: RENDER_FPS, budget: RENDER_BUDGET });
  }

  renderNow() {
    const start = performance.now();
    this.renderer.render(this.scene, this.camera);
    // WebGL works asynchronously (in Chromium, in another process): wait for it, so that the
    // time measured (here and by the frame clock) is what the render cost.
    this.renderer.getContext().finish();
    this.renders = (this.renders ?? 0) + 1;
    // What the canvas holds (its drawing buffer is preserved): which render, and the robot's
    // position [m, wall frame] in it. Tests read it together with the canvas's pixels, so that
    // a picture is known to show the pose they wait for.
    this.drawn = { render: this.renders, position: this.robot.position.toArray() };
    if (this.resolution.add(performance.now() - start)) {
      this.renderer.setPixelRatio(this.resolution.scale);  // the canvas keeps its CSS size
      this.drawn = null;  // a new pixel ratio clears the canvas until the next render
      this.requestRender();
    }
  }

  /** Builds the robot from the viewer's robot shape (robot frame R, metres). */
  setRobot(shape) {
    this.robot.clear();
    this.shape = shape;
    this.chamberMeshes = shape.chambers.map((chamber) => {
      const outline = new THREE.Shape(chamber.outline.map(([x, y]) => new THREE.Vector2(x, y)));
      const mesh = new THREE.Mesh(new THREE.ShapeGeometry(outline),
        new THREE.MeshBasicMaterial({ color: 0xdddddd, side: THREE.DoubleSide, transparent: true, opacity: 0.9 }));
      mesh.position.z = PLATE_Z_M;
      this.robot.add(mesh);
      return mesh;
    });
    this.segmentMeshes = {};
    for (const segment of shape.segments) {
      const mesh = new THREE.Mesh(ribbon(segment.line, shape.strip_width_m),
        new THREE.MeshBasicMaterial({ color: 0x33bb55, side: THREE.DoubleSide }));
      mesh.position.z = PLATE_Z_M + 0.002;
      this.robot.add(mesh);
      this.segmentMeshes[segment.name] = { mesh, length: segment.length_m };
    }
    // The body and wheels as the scene has them (robot_shape.hpp's body_mesh): the body
    // translucent, the wheels dark.
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(shape.body_mesh.positions, 3));
    geometry.setIndex(shape.body_mesh.indices);
    const bodyIndices = 3 * shape.body_mesh.body_triangles;
    geometry.addGroup(0, bodyIndices, 0);
    geometry.addGroup(bodyIndices, shape.body_mesh.indices.length - bodyIndices, 1);
    geometry.computeVertexNormals();
    const body = new THREE.Mesh(geometry, [
      new THREE.MeshLambertMaterial({ color: 0x9fb4c8, transparent: true, opacity: 0.25, side: THREE.DoubleSide }),
      new THREE.MeshLambertMaterial({ color: 0x222222 }),
    ]);
    this.robot.add(body);
    const xAxis = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 0, 0.125),
      shape.body_radius_m * 0.9, 0xffffff, 0.06, 0.04);
    this.robot.add(xAxis);
    this.wheelArrows = shape.wheels.map((wheel) => {
      const [x, y] = wheel.position;
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(x, y, 0.01), 0.1, 0xffd84a, 0.04, 0.025);
      this.robot.add(arrow);
      return arrow;
    });
    this.forceArrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, -1), new THREE.Vector3(0, 0, 0.2), 0.2, 0xff5a4f, 0.05, 0.035);
    this.robot.add(this.forceArrow);
    this.requestRender();
  }

  /**
   * Shows one state: pose {position [x,y,z], quaternion [w,x,y,z] or rpy [roll,pitch,yaw]},
   * pressures [N chambers, then the reservoir] Pa, leak {segment: area m²}, wheels normal [N], force {F, pfx, pfy}.
   */
  update(state) {
    if (state.pose && state.pose.position.every(Number.isFinite)) {
      const [x, y, z] = state.pose.position;
      this.robot.position.set(x, y, z);
      if (state.pose.quaternion) {
        const [w, qx, qy, qz] = state.pose.quaternion;
        this.robot.quaternion.set(qx, qy, qz, w);
      } else if (state.pose.rpy) {
        const [roll, pitch, yaw] = state.pose.rpy;
        this.robot.quaternion.setFromEuler(new THREE.Euler(roll, pitch, yaw, 'ZYX'));
      }
      if (this.follow) {
        const delta = new THREE.Vector3(x, y, z).sub(this.robotPosition);
        this.camera.position.add(delta);
        this.controls.target.add(delta);
        this.controls.update();
      }
      this.robotPosition.set(x, y, z);
    }
    if (this.shape && state.pressures) {
      const ambient = this.shape.ambient_pa;
      this.chamberMeshes.forEach((mesh, i) => {
        const [r, g, b] = suctionColor(ambient - state.pressures[i], SUCTION_MAX_PA);
        mesh.material.color.setRGB(r, g, b);
      });
    }
    if (this.shape && state.leak) {
      for (const [name, area] of Object.entries(state.leak)) {
        const entry = this.segmentMeshes[name];
        if (!entry) continue;
        const [r, g, b] = gapColor(area / entry.length, GAP_MAX_M);
        entry.mesh.material.color.setRGB(r, g, b);
      }
    }
    if (this.shape && state.normal) {
      this.wheelArrows.forEach((arrow, i) => {
        const length = Math.max(0.001, (state.normal[i] ?? 0) * NEWTON_TO_M_WHEEL);
        arrow.setLength(length, Math.min(0.04, length * 0.4), 0.025);
      });
    }
    if (this.shape && state.force) {
      const length = Math.max(0.001, state.force.F * NEWTON_TO_M_FORCE);
      this.forceArrow.position.set(state.force.pfx, state.force.pfy, length + 0.005);
      this.forceArrow.setLength(length, Math.min(0.05, length * 0.3), 0.035);
    }
    this.requestRender();
  }

  /** The wall under the robot from a depth message {size, cell_m, heights_mm}. */
  setHeights(depth) {
    const n = depth.size;
    const span = (n - 1) * depth.cell_m;
    if (!this.heightMesh || this.heightMesh.userData.n !== n) {
      if (this.heightMesh) this.robot.remove(this.heightMesh);
      const geometry = new THREE.PlaneGeometry(span, span, n - 1, n - 1);
      geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(n * n * 3), 3));
      this.heightMesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide, transparent: true, opacity: 1 }));
      this.heightMesh.userData.n = n;
      this.robot.add(this.heightMesh);
    }
    this.lastHeights = depth;
    const position = this.heightMesh.geometry.attributes.position;
    const color = this.heightMesh.geometry.attributes.color;
    // PlaneGeometry's vertices run row by row from (-x, +y), as the depth image's pixels.
    for (let i = 0; i < n * n; ++i) {
      const h = depth.heights_mm[i] * 1e-3;
      position.setZ(i, h * this.relief);
      const [r, g, b] = heightColor(h, HEIGHT_RANGE_M);
      color.setXYZ(i, r, g, b);
    }
    position.needsUpdate = true;
    color.needsUpdate = true;
    this.heightMesh.geometry.computeVertexNormals();
    this.requestRender();
  }

  setRelief(relief) {
    this.relief = relief;
    if (this.lastHeights) this.setHeights(this.lastHeights);
  }

  /** Appends a point to the track if it moved more than 2 mm. */
  addTrackPoint([x, y, z]) {
    const n = this.trackCount;
    if (n > 0) {
      const dx = x - this.trackPositions[3 * n - 3];
      const dy = y - this.trackPositions[3 * n - 2];
      if (dx * dx + dy * dy < 4e-6) return;
    }
    if (n >= MAX_TRACK) return;
    this.trackPositions.set([x, y, z + 0.002], 3 * n);
    this.trackCount = n + 1;
    this.track.geometry.setDrawRange(0, this.trackCount);
    this.track.geometry.attributes.position.needsUpdate = true;
  }

  /** Replaces the track (replay: the path up to the slider's time). */
  setTrack(points) {
    this.trackCount = 0;
    for (const p of points) this.addTrackPoint(p);
    this.track.geometry.setDrawRange(0, this.trackCount);
    this.requestRender();
  }

  /** 'follow' toggles following; 'top' and 'behind' place the camera relative to the robot. */
  setView(kind) {
    const p = this.robotPosition;
    if (kind === 'top') {
      this.camera.position.set(p.x, p.y, p.z + 2.2);
    } else if (kind === 'behind') {
      this.camera.position.set(p.x + 0.01, p.y - 0.3, p.z - 1.8);
    }
    this.camera.up.set(0, 1, 0);
    this.controls.target.copy(p);
    this.controls.update();
    if (this.heightMesh) this.heightMesh.material.opacity = kind === 'behind' ? 0.35 : 1;
    this.requestRender();
  }
}

/** A flat strip of `width` along a polyline [[x, y], ...] in the plane z = 0. */
function ribbon(line, width) {
  const positions = [];
  const indices = [];
  for (let i = 0; i < line.length; ++i) {
    const [x0, y0] = line[Math.max(0, i - 1)];
    const [x1, y1] = line[Math.min(line.length - 1, i + 1)];
    let nx = -(y1 - y0);
    let ny = x1 - x0;
    const len = Math.hypot(nx, ny) || 1;
    nx = (nx / len) * width / 2;
    ny = (ny / len) * width / 2;
    const [x, y] = line[i];
    positions.push(x + nx, y + ny, 0, x - nx, y - ny, 0);
    if (i > 0) {
      const a = 2 * (i - 1);
      indices.push(a, a + 1, a + 2, a + 1, a + 3, a + 2);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setIndex(indices);
  return geometry;
}
