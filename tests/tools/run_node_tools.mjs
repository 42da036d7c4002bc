// Runs many calls of the npm glTF tools (gltf-transform, gltfpack, obj2gltf)
// in one node process: starting node and loading a tool costs about 0.2 s
// (gltfpack) to 1 s (gltf-transform, obj2gltf) a call, far more than the work
// of a call on the test models.
//
// usage: node run_node_tools.mjs TOOLS_DIR JOBS_FILE
//   TOOLS_DIR: the folder of scripts/install-node-tools (TOOLS_DIR/node_modules).
//   JOBS_FILE: one job a line, fields separated by tabs:
//     FOLDER<TAB>LOG<TAB>TOOL<TAB>ARGUMENT...
//   TOOL is gltf-transform, gltfpack or obj2gltf; the arguments are those of
//   the tool's command line, which each job goes through as the CLI does:
//     gltf-transform: the CLI's own command program (@gltf-transform/cli's
//       program, on caporal, what bin/cli.js runs), so the same parsing,
//       defaults and session (read, transform, write) as the command;
//     gltfpack: its library's pack() with the arguments, the call its cli.js makes;
//     obj2gltf: only `-i IN -o OUT` and `--version`: the library with the
//       options its bin/obj2gltf.js builds from those (the defaults; .glb
//       output when OUT ends in .glb).
//   Each job runs in FOLDER (the working folder of a CLI call); what the tool
//   prints goes to LOG, as the CLI would print it (a failure's message too).
// Prints "STATUS<TAB>LOG" per job when it ends (0 made, 1 failed); a job
// whose line is missing is for the caller to run again with the tool's own
// command. Missing are: the jobs after the process died or was stopped; and
// the jobs from a gltf-transform or gltfpack failure on, that one included:
// the process then stops, as the state of their WebAssembly modules (Draco,
// meshoptimizer, gltfpack) after an error is not known, and the command gives
// the failure's own message. A tool that cannot be loaded here (its
// package's layout changed) stops it too. obj2gltf is plain JavaScript: its
// failures are reported (status 1, its message as its CLI prints it).
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';

const [toolsDir, jobsFile] = process.argv.slice(2);
if (!toolsDir || !jobsFile) {
  process.stderr.write('usage: node run_node_tools.mjs TOOLS_DIR JOBS_FILE\n');
  process.exit(2);
}
const modules = path.resolve(toolsDir, 'node_modules');
const requireTool = createRequire(path.join(modules, 'run_node_tools.cjs'));
const moduleUrl = (p) => pathToFileURL(path.join(modules, p)).href;

// The tools, loaded on first use.
const loaded = {};
const loaders = {
  async 'gltf-transform'() {
    // bin/cli.js: `programReady.then(() => program.run())`, where run() hands
    // process.argv to caporal's program (the same module instance as here),
    // and caporal reports a failed command through its 'error' event (the
    // message as "error: ...", exit status 1).
    process.argv[1] = path.join(modules, '.bin', 'gltf-transform');  // caporal's program name (help text)
    const { program, programReady } = await import(moduleUrl('@gltf-transform/cli/dist/cli.mjs'));
    const { program: caporal } = await import(moduleUrl('@donmccurdy/caporal/dist/caporal.modern.js'));
    program.disableGlobalOption('--silent');
    await programReady;
    if (!caporal.getCommands().some((c) => c.name === 'draco')) {
      throw new Error('@donmccurdy/caporal loaded here is not the instance of @gltf-transform/cli');
    }
    return async (args) => {
      try {
        await caporal.run(args);
      } catch (err) {
        caporal.emit('error', err);
      }
    };
  },
  async gltfpack() {
    const { pack } = await import(moduleUrl('gltfpack/library.js'));
    const iface = { read: (p) => fs.readFileSync(p), write: (p, data) => fs.writeFileSync(p, data) };
    return async (args) => {
      try {
        process.stdout.write(await pack(args, iface));
      } catch (err) {
        process.stderr.write(err.message);
        process.exitCode = 1;
      }
    };
  },
  async obj2gltf() {
    const obj2gltf = requireTool('obj2gltf');
    const version = requireTool('obj2gltf/package.json').version;
    return async (args) => {
      if (args.length === 1 && args[0] === '--version') {
        console.log(version);
        return;
      }
      if (args.length !== 4 || args[0] !== '-i' || args[2] !== '-o') {
        throw new Error('run_node_tools.mjs: obj2gltf takes only -i IN -o OUT here');
      }
      // bin/obj2gltf.js with only -i and -o: every option at its default.
      const objPath = path.resolve(args[1]);
      const filename = path.resolve(args[3]);
      const binary = path.extname(filename).toLowerCase() === '.glb';
      const gltfPath = path.join(path.dirname(filename), path.basename(filename, path.extname(filename)) + (binary ? '.glb' : '.gltf'));
      const d = obj2gltf.defaults;
      const options = {
        binary,
        separate: d.separate,
        separateTextures: d.separateTextures,
        checkTransparency: d.checkTransparency,
        secure: d.secure,
        packOcclusion: d.packOcclusion,
        metallicRoughness: d.metallicRoughness,
        specularGlossiness: d.specularGlossiness,
        unlit: d.unlit,
        overridingTextures: {},
        outputDirectory: path.dirname(filename),
        inputUpAxis: 'Y',
        outputUpAxis: 'Y',
        triangleWindingOrderSanitization: d.triangleWindingOrderSanitization,
        doubleSidedMaterial: d.doubleSidedMaterial,
      };
      console.time('Total');
      try {
        const gltf = await obj2gltf(objPath, options);
        if (binary) fs.writeFileSync(gltfPath, gltf);
        else fs.writeFileSync(gltfPath, JSON.stringify(gltf, null, 2) + '\n');
        console.timeEnd('Total');
      } catch (error) {
        console.log(error.message);
        process.exitCode = 1;
        discarding(() => console.timeEnd('Total'));  // the CLI's process ends with its timer running
      }
    };
  },
};

// What the tools print goes to the job's log: the writes of process.stdout
// and process.stderr (console.log and the loggers end there) are redirected.
const realStdoutWrite = process.stdout.write.bind(process.stdout);
let logFd = null;
let discard = false;
function discarding(f) {
  discard = true;
  try {
    f();
  } finally {
    discard = false;
  }
}
for (const stream of [process.stdout, process.stderr]) {
  const original = stream.write.bind(stream);
  stream.write = (chunk, encoding, callback) => {
    if (logFd === null) return original(chunk, encoding, callback);
    if (!discard) fs.writeSync(logFd, typeof chunk === 'string' ? chunk : Buffer.from(chunk));
    if (typeof encoding === 'function') encoding();
    else if (typeof callback === 'function') callback();
    return true;
  };
}

const jobs = fs.readFileSync(jobsFile, 'utf8').split('\n').filter((l) => l.length > 0);
const home = process.cwd();
for (const line of jobs) {
  const [folder, log, tool, ...args] = line.split('\t');
  if (!loaders[tool]) {
    process.stderr.write(`run_node_tools.mjs: unknown tool '${tool}' in ${jobsFile}\n`);
    process.exit(2);
  }
  logFd = fs.openSync(log, 'w');
  process.exitCode = 0;
  let loadFailed = false;
  try {
    process.chdir(folder || home);
    try {
      loaded[tool] ??= await loaders[tool]();
    } catch (err) {
      loadFailed = true;
      throw err;
    }
    await loaded[tool](args);
  } catch (err) {
    process.stderr.write(`${err && err.stack ? err.stack : err}\n`);
    process.exitCode = 1;
  }
  const status = process.exitCode ? 1 : 0;
  fs.closeSync(logFd);
  logFd = null;
  process.exitCode = 0;
  if (status !== 0 && (loadFailed || tool !== 'obj2gltf')) {
    process.stderr.write(`run_node_tools.mjs: ${tool} failed on ${log}: stopping here (the rest by the commands)\n`);
    process.exit(3);
  }
  realStdoutWrite(`${status}\t${log}\n`);
}
