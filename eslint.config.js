import js from '@eslint/js';
import globals from 'globals';

export default [
	{ ignores: [ 'web/dist/**', 'node_modules/**', '.venv/**', 'assets/**' ] },
	js.configs.recommended,
	{
		files: [ 'web/src/**/*.js' ],
		languageOptions: { ecmaVersion: 2022, sourceType: 'module', globals: globals.browser },
	},
	{
		// The kernels are plain functions over typed arrays, shared with Node (tests, benchmarks):
		// three.js and its add-ons belong to web/src/scene and web/src/ui.
		files: [ 'web/src/core/**/*.js' ],
		rules: {
			'no-restricted-imports': [ 'error', {
				paths: [
					{ name: 'three', message: 'web/src/core never imports three.js: scene objects in web/src/scene call the kernels.' },
					{ name: 'three-mesh-bvh', message: 'web/src/core never imports three-mesh-bvh.' },
				],
				patterns: [
					{ group: [ 'three/*', 'three-mesh-bvh/*' ], message: 'web/src/core never imports three.js or its add-ons.' },
				],
			} ],
		},
	},
	{
		files: [ 'tests/js/**/*.js', 'e2e/**/*.js', 'bench/**/*.mjs', 'scripts/**/*.mjs', 'web/vite.config.js' ],
		languageOptions: { ecmaVersion: 2022, sourceType: 'module', globals: { ...globals.node, ...globals.browser } },
	},
];
