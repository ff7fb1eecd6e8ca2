// Runs the Khronos glTF validator (npm gltf-validator) over the given .gltf/.glb files and prints
// one JSON array on stdout: per file its path and every issue the validator reports as an error,
// with its code, JSON pointer and message. External resources resolve next to each file.
//   node validate.mjs VALIDATOR_MODULE_DIR FILE...
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { createRequire } from 'node:module';

const [validatorDir, ...files] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(validatorDir), 'index.js'));
const validator = require(path.resolve(validatorDir, 'node_modules/gltf-validator'));

// The validator itself can die on hostile input (its recursion over a deep node hierarchy overflows
// the stack, thrown outside any promise): that file's validation fails, and the others go on.
let failCurrent = () => {};
process.on('uncaughtException', (error) => failCurrent(error));

function validate(bytes, options) {
  return new Promise((resolve, reject) => {
    failCurrent = reject;
    validator.validateBytes(bytes, options).then(resolve, reject);
  });
}

const results = [];
for (const file of files) {
  const entry = { file, errors: [], warnings: 0 };
  try {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validate(bytes, {
      uri: path.basename(file),
      maxIssues: 0,
      // Inside the asset's folder only, as lghd's asset sandbox: no absolute paths, no "..".
      externalResourceFunction: (uri) => {
        const relative = decodeURIComponent(uri);
        if (path.isAbsolute(relative) || relative.split(/[\\/]/).includes('..') ||
            /^[a-z][a-z0-9+.-]*:/i.test(relative)) {
          return Promise.reject(new Error(`${uri} leaves the asset's folder`));
        }
        return readFile(path.join(path.dirname(file), relative)).then(
          (data) => new Uint8Array(data));
      },
    });
    for (const message of report.issues.messages) {
      if (message.severity === 0) {
        entry.errors.push({ code: message.code, pointer: message.pointer ?? '',
                            message: message.message });
      } else if (message.severity === 1) {
        entry.warnings += 1;
      }
    }
  } catch (error) {
    entry.errors.push({ code: 'VALIDATOR_FAILED', pointer: '', message: String(error) });
  }
  results.push(entry);
}
process.stdout.write(JSON.stringify(results, null, 1) + '\n');
