// Bundles the viewer's page with esbuild from the npm packages installed by `npm ci` into the
// build directory: node build.mjs --modules <node_modules> --out <dir>.
import { copyFileSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const args = process.argv.slice(2);
const option = (name) => {
  const at = args.indexOf(name);
  if (at < 0 || at + 1 >= args.length) {
    console.error(`build.mjs: missing ${name} <dir>`);
    process.exit(2);
  }
  return args[at + 1];
};
const modules = option('--modules');
const out = option('--out');
const here = dirname(fileURLToPath(import.meta.url));
const esbuild = await import(pathToFileURL(join(modules, 'esbuild', 'lib', 'main.js')).href);

mkdirSync(out, { recursive: true });
await esbuild.build({
  entryPoints: [join(here, 'src', 'main.js')],
  bundle: true,
  format: 'esm',
  target: ['es2020'],
  minify: true,
  sourcemap: true,
  nodePaths: [modules],
  outfile: join(out, 'viewer.js'),
  logLevel: 'warning',
  legalComments: 'linked',
});
for (const file of ['index.html', 'style.css']) copyFileSync(join(here, file), join(out, file));
