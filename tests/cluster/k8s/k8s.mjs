// The Kubernetes Jobs of deploy/ (after envsubst) against the Kubernetes API
// schema, offline: kubernetes-models ships the batch/v1 Job schema compiled
// from the Kubernetes OpenAPI document (types, enums, required fields).  JSON
// schema lets unknown fields through, while the API server refuses them
// (kubectl's default --validate=strict), so every key the validator never
// reads, in an object it does not enumerate (a map), is reported too.
//
//   node k8s.mjs check FILE...          exit 1 on any error, each printed
//   node k8s.mjs command FILE ROOT      the container's env and command,
//        NUL-separated (KEY=VALUE..., then the argv), each volume's
//        mountPath replaced by ROOT/<volume name>: to run it here
//   node k8s.mjs failjob FILE           exit codes that fail the Job at once
import { readFileSync } from "node:fs";
import { Job } from "kubernetes-models/batch/v1";
import { parse } from "yaml";

// A proxy per object that records the keys read and whether keys were listed.
function watch(value, path, seen, proxies) {
  if (value === null || typeof value !== "object") return value;
  if (proxies.has(value)) return proxies.get(value);
  const rec = { path, value, read: new Set(), listed: false };
  seen.push(rec);
  const proxy = new Proxy(value, {
    get(target, key, receiver) {
      const v = Reflect.get(target, key, receiver);
      if (typeof key !== "string" || !Object.hasOwn(target, key)) return v;
      rec.read.add(key);
      return watch(v, `${path}/${key}`, seen, proxies);
    },
    ownKeys(target) {
      rec.listed = true;
      return Reflect.ownKeys(target);
    },
  });
  proxies.set(value, proxy);
  return proxy;
}

function check(file) {
  const job = parse(readFileSync(file, "utf8"));
  const seen = [];
  const errors = [];
  if (job?.apiVersion !== "batch/v1" || job?.kind !== "Job") errors.push("not a batch/v1 Job");
  try {
    Job.prototype.validate.call(watch(job, "", seen, new WeakMap())); // the schema's check, on the proxy
  } catch (e) {
    errors.push(e.message);
  }
  for (const { path, value, read, listed } of seen)
    if (!listed && !Array.isArray(value))
      for (const key of Object.keys(value))
        if (!read.has(key)) errors.push(`${path}/${key}: unknown field`);
  for (const e of errors) console.error(`${file}: ${e}`);
  return errors.length === 0;
}

function command(file, root) {
  const pod = parse(readFileSync(file, "utf8")).spec.template.spec;
  const c = pod.containers[0];
  const mounts = (c.volumeMounts ?? []).sort((a, b) => b.mountPath.length - a.mountPath.length);
  const local = (s) =>
    mounts.reduce(
      (t, m) => t.replace(new RegExp(`(^|[\\s"'=])${m.mountPath}(?=/|$|\\s)`, "g"), `$1${root}/${m.name}`),
      s,
    );
  const env = (c.env ?? []).map((e) => `${e.name}=${e.value}`);
  process.stdout.write([...env, ...c.command.map(local), ...(c.args ?? []).map(local)].join("\0") + "\0");
}

function failjob(file) {
  const rules = parse(readFileSync(file, "utf8")).spec.podFailurePolicy?.rules ?? [];
  const codes = rules.filter((r) => r.action === "FailJob" && r.onExitCodes?.operator === "In");
  console.log(codes.flatMap((r) => r.onExitCodes.values).join(" "));
}

const [mode, ...args] = process.argv.slice(2);
if (mode === "check") process.exit(args.map(check).every(Boolean) ? 0 : 1);
else if (mode === "command") command(args[0], args[1]);
else if (mode === "failjob") failjob(args[0]);
else {
  console.error("usage: node k8s.mjs check FILE... | command FILE ROOT | failjob FILE");
  process.exit(2);
}
