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
      "/api": { target: server, ws: true },
    },
  },
});
