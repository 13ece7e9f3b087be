// run.mcap read with Foxglove's own libraries, as Foxglove and Lichtblick read it (docs/recordings.md):
// @mcap/core's indexed reader (fzstd for the zstd chunks), every channel's schema parsed by
// @foxglove/omgidl-parser and every message decoded by @foxglove/omgidl-serialization, the
// Foxglove channels included; the decoded values against the run's trace.csv.
//
//   node read_run_mcap.mjs --build BUILD --root ROOT --mode solo|distributed --out RUN_DIR --modules NODE_MODULES
//
// Runs crack-descent for 4 s (climbsim-solo, or the launcher), then checks; exit 0 or a thrown
// error naming the channel, the time and both values.

import { execFileSync } from "node:child_process";
import { open, readFile, rm } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";
import { parseArgs } from "node:util";

const { values: args } = parseArgs({
  options: {
    build: { type: "string" }, root: { type: "string" }, mode: { type: "string" }, out: { type: "string" },
    modules: { type: "string" },  // node_modules of this folder's package-lock.json (npm ci in the build)
  },
});
const require = createRequire(path.join(args.modules, "index.js"));
const { McapIndexedReader } = require("@mcap/core");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const { decompress } = require("fzstd");

function fail(message) {
  throw new Error(message);
}

async function runScenario() {
  await rm(args.out, { recursive: true, force: true });
  const common = ["crack-descent", "--set", "duration_s=4", "--out", args.out];
  if (args.mode === "solo") {
    execFileSync(`${args.build}/bin/climbsim-solo`, [...common, "--no-plots"], { stdio: "ignore" });
  } else {
    execFileSync(`${args.build}/bin/climbsim-compose`, ["--root", args.root, "--build", args.build, "run", ...common],
      { stdio: "ignore" });
  }
}

/** trace.csv as {columns, rows by t_ns}. */
async function readTrace(path) {
  const lines = (await readFile(path, "utf8")).trim().split("\n");
  const columns = lines[0].split(",");
  const rows = new Map();
  for (const line of lines.slice(1)) {
    const cells = line.split(",").map(Number);
    rows.set(BigInt(Math.round(cells[0] * 1e9)), Object.fromEntries(columns.map((c, i) => [c, cells[i]])));
  }
  return rows;
}

async function main() {
  await runScenario();
  const file = await open(`${args.out}/run.mcap`, "r");
  const readable = {
    size: async () => BigInt((await file.stat()).size),
    read: async (offset, size) => {
      const buffer = new Uint8Array(Number(size));
      await file.read(buffer, 0, Number(size), Number(offset));
      return buffer;
    },
  };
  const reader = await McapIndexedReader.Initialize({
    readable,
    decompressHandlers: { zstd: (data, size) => decompress(data, new Uint8Array(Number(size))) },
  });
  const decoders = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    if (schema.encoding !== "omgidl" || channel.messageEncoding !== "cdr") {
      fail(`${channel.topic}: ${schema.encoding}/${channel.messageEncoding}`);
    }
    const definitions = parseIDL(new TextDecoder().decode(schema.data));
    decoders.set(id, { topic: channel.topic, reader: new MessageReader(schema.name, definitions) });
  }

  const rows = await readTrace(`${args.out}/trace.csv`);
  const byTopic = new Map();
  for await (const message of reader.readMessages()) {
    const { topic, reader: decoder } = decoders.get(message.channelId);
    const value = decoder.readMessage(message.data);
    if (!byTopic.has(topic)) byTopic.set(topic, []);
    byTopic.get(topic).push({ t: message.logTime, value });
  }
  const dt = BigInt(byTopic.get("clock/RunStart")[0].value.dt_ns);
  const expect = (topic, t, column, got) => {
    const row = rows.get(t);
    if (!row) fail(`${topic}: no trace row at t = ${t} ns`);
    if (row[column] !== got) fail(`${topic} at t = ${t} ns: ${column} is ${row[column]} in trace.csv, ${got} decoded`);
  };
  // A producer's sample is the trace's row one step later; its initial state (the first, at 0) is row 0.
  const rowOf = (i, t) => (i === 0 ? 0n : t + dt);
  byTopic.get("thermo/AdhesionForce").forEach(({ t, value }, i) => expect("AdhesionForce", rowOf(i, t), "downforce_n", value.downforce_n));
  byTopic.get("thermo/ChamberState").forEach(({ t, value }, i) => expect("ChamberState", rowOf(i, t), "pr_pa", value.pressure_pa[7]));
  byTopic.get("drive/RobotState").forEach(({ t, value }, i) => expect("RobotState", rowOf(i, t), "x_m", value.position_m[0]));
  byTopic.get("drive/DriveState").forEach(({ t, value }, i) =>
    expect("DriveState", rowOf(i, t), "wheel1_normal_n", value.wheels[0].normal_force_n));
  for (const { value } of byTopic.get("sealing/Leakage")) {
    if (value.segments.length !== 18) fail(`Leakage with ${value.segments.length} segments`);
  }
  // The Foxglove channels: the transform is the pose of the row at its time.
  for (const { t, value } of byTopic.get("foxglove/transforms")) {
    const tf = value.transforms[0];
    if (tf.parent_frame_id !== "wall" || tf.child_frame_id !== "robot") fail(`transform ${tf.parent_frame_id} -> ${tf.child_frame_id}`);
    if (BigInt(tf.timestamp.sec) * 1000000000n + BigInt(tf.timestamp.nsec) !== t) fail(`transform stamped off its log time ${t}`);
    expect("foxglove/transforms", t, "y_m", tf.translation.y);
  }
  for (const { value } of byTopic.get("foxglove/robot")) {
    const entity = value.entities[0];
    if (entity.frame_id !== "robot" || entity.triangles.length !== 7 || entity.arrows.length !== 4) {
      fail(`scene entity ${entity.frame_id}: ${entity.triangles.length} triangle lists, ${entity.arrows.length} arrows`);
    }
    for (const tri of entity.triangles) {
      if (tri.points.length === 0 || tri.points.length % 3 !== 0 || !(tri.color.r >= 0 && tri.color.r <= 1)) {
        fail(`chamber triangles: ${tri.points.length} points, red ${tri.color.r}`);
      }
    }
  }
  const grids = byTopic.get("foxglove/depth_grid") ?? fail("no foxglove/depth_grid");
  const reduced = byTopic.get("scene/DepthGrid") ?? fail("no scene/DepthGrid");
  if (grids.length !== reduced.length) fail(`${grids.length} foxglove grids of ${reduced.length} depth grids`);
  grids.forEach(({ value }, i) => {
    if (value.data.length !== value.column_count * value.row_stride || value.fields[0].name !== "height_m") {
      fail(`grid of ${value.column_count} columns with ${value.data.length} bytes`);
    }
    // Its first row is the depth grid's last (rows go up along y).
    const n = reduced[i].value.size;
    const first = new DataView(value.data.buffer, value.data.byteOffset, 4).getFloat32(0, true);
    if (first !== reduced[i].value.height_m[(n - 1) * n]) fail(`grid ${i}: first cell ${first}`);
  });
  await file.close();
  const counts = [...byTopic].map(([topic, list]) => `${topic} ${list.length}`).join(", ");
  console.log(`read_run_mcap: ${args.out}/run.mcap decoded with Foxglove's libraries: ${counts}`);
}

await main();
