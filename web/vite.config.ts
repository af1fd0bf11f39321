// Builds the HMI into dist/, which the server serves at "/".
// `npm run dev` serves the sources with hot reload and forwards the API to a running server
// (NCTWIN_URL, default http://127.0.0.1:8080).
import { defineConfig } from "vite";

const server = process.env.NCTWIN_URL ?? "http://127.0.0.1:8080";

export default defineConfig({
  base: "./",
  build: {
    outDir: "dist",
    emptyOutDir: true,
    // three.js alone is ~700 kB minified; one chunk is fine for a local operator screen.
    chunkSizeWarningLimit: 1200,
  },
  server: {
    proxy: {
      // The server answers only to its own Host and to pages of its own origin (README,
      // "Cross-site requests"): the proxy sends the target's Host, and a request from this dev
      // server's own page goes on as one of the target's own origin. Pages of other origins
      // keep theirs and are refused.
      "/api": {
        target: server,
        ws: true,
        changeOrigin: true,
        configure: (proxy) => {
          const ownOrigin = (req: { headers: Record<string, string | string[] | undefined> }) =>
            req.headers.origin !== undefined && req.headers.origin === `http://${req.headers.host}`;
          const rewrite = (
            proxyReq: { setHeader(name: string, value: string): void },
            req: { headers: Record<string, string | string[] | undefined> },
          ) => {
            if (ownOrigin(req)) proxyReq.setHeader("origin", new URL(server).origin);
          };
          proxy.on("proxyReq", rewrite);
          proxy.on("proxyReqWs", rewrite);
        },
      },
    },
  },
});
