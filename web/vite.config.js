import { defineConfig } from 'vite';

// `holey serve --web web/dist` serves the build from `/`; relative asset
// paths keep it working behind any prefix as well.
export default defineConfig({
  base: './',
  build: { outDir: 'dist', emptyOutDir: true, chunkSizeWarningLimit: 1000 },
  server: {
    // `npm run dev` proxies the API to a running `holey serve` (or the mock).
    proxy: {
      '/ws': { target: 'ws://127.0.0.1:' + (process.env.HOLEY_PORT || 8080), ws: true },
      '/api': 'http://127.0.0.1:' + (process.env.HOLEY_PORT || 8080),
    },
  },
});
