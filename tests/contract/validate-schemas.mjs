// Every proto/*.schema.json against the JSON Schema 2020-12 meta-schema, compiled by a 2020-12
// validator (Ajv) in strict mode, which refuses unknown keywords and ambiguous forms. OpenAPI's
// discriminator is an annotation of the OpenAPI 3.1 dialect: known to Ajv as one, not validated.
//   node validate-schemas.mjs PROTO_DIR
import fs from "node:fs";
import path from "node:path";
import Ajv2020 from "ajv/dist/2020.js";

const dir = process.argv[2];
const ajv = new Ajv2020({ strict: true, allowUnionTypes: true, allErrors: true });
ajv.addKeyword({ keyword: "discriminator" });
// The formats the schemas use (Ajv knows none without the ajv-formats package): RFC 3339.
ajv.addFormat("date-time", /^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d+)?(Z|[+-]\d\d:\d\d)$/);
const files = fs.readdirSync(dir).filter((name) => name.endsWith(".schema.json")).sort();
for (const name of files) {
  const schema = JSON.parse(fs.readFileSync(path.join(dir, name), "utf8"));
  if (schema.$schema !== "https://json-schema.org/draft/2020-12/schema") {
    throw new Error(`${name}: $schema is ${schema.$schema}, not 2020-12`);
  }
  if (!ajv.validateSchema(schema)) {
    throw new Error(`${name}: ${ajv.errorsText(ajv.errors)}`);
  }
  ajv.addSchema(schema, name);  // keyed by file name: the relative $refs resolve among them
}
for (const name of files) ajv.getSchema(name);  // compiles, resolving every $ref
console.log(`validate-schemas: ${files.length} schemas are valid JSON Schema 2020-12`);
